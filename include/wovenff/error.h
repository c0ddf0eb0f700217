/* wovenff — error reporting shared by every part of the C core.
 *
 * Functions that can fail return 0 on success and -1 on failure, and fill a
 * caller-owned wff_error with one human-readable line that names the file,
 * line, key, element or parameter at fault. Nothing is allocated. */
#ifndef WOVENFF_ERROR_H
#define WOVENFF_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

/* Longest message kept; longer ones are truncated (never overflow). */
#define WFF_ERROR_MAX 512

typedef struct wff_error {
    char message[WFF_ERROR_MAX];
} wff_error;

/* printf-style: writes the message into err (if err is not NULL) and returns -1,
 * so a failing path can say `return wff_fail(err, "...", ...);`. */
int wff_fail(wff_error *err, const char *format, ...)
    __attribute__((format(printf, 2, 3)));

#ifdef __cplusplus
}
#endif
#endif
