/* ply_contact.c: kinematic contact between neighbouring plies of a pack
 * (include/wovenff/pack.h). */
#include "pack.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void wff_ply_contact_free(struct wff_pack *P)
{
    free(P->cand_start);
    free(P->cand);
    free(P->impulse);
    free(P->touched);
    free(P->touched_list);
    free(P->facet_x);
    P->cand_start = P->cand = P->touched_list = NULL;
    P->impulse = P->facet_x = NULL;
    P->touched = NULL;
}

int wff_ply_contact_refresh(wff_model *m, wff_error *err)
{
    (void)m;
    (void)err;
    return 0;
}

int wff_ply_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    (void)m;
    (void)dt;
    (void)dt_mid;
    (void)err;
    return 0;
}
