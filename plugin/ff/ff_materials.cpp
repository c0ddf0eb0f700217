// wovenff FreeFEM binding: the material handle table.
//
//   int mat = wovenffMaterial("freefem_scripts/materials/kevlar_s706.txt");
//
// loads and validates a material file once; every pointwise function
// (ff_point.cpp, ff_explore.cpp) takes the handle in place of the file name,
// so a script's loop no longer re-reads the file on every call. A handle is
// a snapshot: the file is not read again (load it again for a new handle).
// FreeFEM passes no user data to functions, so the table is the binding's
// (the C core keeps no global state). Handles start at kFirstHandle, so a
// model handle (0, 1, ...) given by mistake is refused, not taken for a
// material. Knows nothing of what the functions do with a material.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <memory>
#include <string>
#include <vector>

#include "ff_wovenff.hpp"

using namespace Fem2D;

namespace {

const long kFirstHandle = 1000000;

// unique_ptr: a material never moves, so a pointer to it stays valid while
// the table grows.
std::vector<std::unique_ptr<wff_material>> &table()
{
    static std::vector<std::unique_ptr<wff_material>> materials;
    return materials;
}

long ffMaterial(string *const &path)
{
    std::unique_ptr<wff_material> mat(new wff_material);
    wff_ff_material("wovenffMaterial", path, mat.get());
    table().push_back(std::move(mat));
    return kFirstHandle + (long)table().size() - 1;
}

} // namespace

const wff_material *wff_ff_material(long id, const char *fn)
{
    const long i = id - kFirstHandle;
    if (i < 0 || i >= (long)table().size()) {
        std::string msg = std::to_string(id) + " is not a wovenff material handle (";
        if (table().empty())
            msg += "none loaded yet";
        else
            msg += "loaded: " + std::to_string(kFirstHandle) + " to " +
                   std::to_string(kFirstHandle + (long)table().size() - 1);
        wff_ff_fail(fn, msg + "; wovenffMaterial(file) returns one)");
    }
    return table()[i].get();
}

const wff_material *wff_ff_material_arg(const char *fn, string *const &path,
                                        wff_material *scratch)
{
    wff_ff_material(fn, path, scratch);
    return scratch;
}

const wff_material *wff_ff_material_arg(const char *fn, const long &id, wff_material *)
{
    return wff_ff_material(id, fn);
}

void wff_ff_register_materials()
{
    Global.Add("wovenffMaterial", "(", new OneOperator1_<long, string *>(ffMaterial));
}
