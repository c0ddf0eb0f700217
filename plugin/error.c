/* error.c: the one way the C core reports a failure: a printf-style message
 * into the caller's wff_error, returning -1 (include/wovenff/error.h).
 * Knows nothing of what failed. */
#include "wovenff/error.h"

#include <stdarg.h>
#include <stdio.h>

int wff_fail(wff_error *err, const char *format, ...)
{
    if (err) {
        va_list args;
        va_start(args, format);
        vsnprintf(err->message, sizeof err->message, format, args);
        va_end(args);
    }
    return -1;
}
