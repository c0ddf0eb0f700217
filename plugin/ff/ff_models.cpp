// wovenff FreeFEM binding: the model handle table every model function shares.
//
// A script gets an integer handle from wovenffModel; every other function
// takes it. FreeFEM passes no user data to functions, so the table lives
// here (binding-level); the C core itself keeps no global state. Each model
// also keeps its last error message for wovenffLastError(md). Knows nothing
// of what the functions do with a model.
#include "ff++.hpp"

#include <cstdlib>
#include <string>
#include <vector>

#include "ff_wovenff.hpp"

namespace {

struct Entry {
    wff_model *model;        // nullptr once freed
    std::string last_error;  // "function: message" of its last failure
};

std::vector<Entry> &table()
{
    static std::vector<Entry> entries;
    return entries;
}

bool live(long id)
{
    return id >= 0 && id < (long)table().size() && table()[id].model;
}

} // namespace

long wff_ff_model_add(wff_model *m)
{
    table().push_back(Entry{m, std::string()});
    return (long)table().size() - 1;
}

wff_model *wff_ff_model(long id, const char *fn)
{
    if (!live(id))
        wff_ff_fail(fn, std::to_string(id) + " is not a live wovenff model handle");
    return table()[id].model;
}

void wff_ff_model_free(long id, const char *fn)
{
    wff_model *m = wff_ff_model(id, fn);
    wff_model_delete(m);
    table()[id].model = nullptr;
}

void wff_ff_model_fail(const char *fn, const std::string &message, long id)
{
    if (id >= 0 && id < (long)table().size())
        table()[id].last_error = std::string(fn) + ": " + message;
    wff_ff_fail(fn, message);
}

std::string wff_ff_model_last_error(long id)
{
    if (id >= 0 && id < (long)table().size())
        return table()[id].last_error;
    return wff_ff_last_error();
}
