/* Accuracy of a ballistic run against a reference run, from their results
 * folders: relative L2 error of the apex history over 0–2.5 ms (the run
 * interpolated onto the reference's times), error of the peak displacement
 * (relative) and of its time (absolute, s), and the relative L2 error of the
 * warp and weft profiles at 2.0 ms. Prints one CSV line:
 *   apex_l2,peak_error,peak_time_error,profile_l2
 * usage: compare REFERENCE_DIR RUN_DIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_ROWS 200000

typedef struct series { int n; double *t, *z; } series;

static int read_history(const char *dir, series *s)
{
    char path[1024], line[4096];
    snprintf(path, sizeof path, "%s/history.csv", dir);
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "compare: cannot open %s\n", path);
        return -1;
    }
    s->t = malloc(sizeof(double) * MAX_ROWS);
    s->z = malloc(sizeof(double) * MAX_ROWS);
    s->n = 0;
    if (!fgets(line, sizeof line, f)) { /* header: time,apex_displacement,... */
        fclose(f);
        return -1;
    }
    while (s->n < MAX_ROWS && fgets(line, sizeof line, f)) {
        double t, z;
        if (sscanf(line, "%lf,%lf", &t, &z) == 2) {
            s->t[s->n] = t;
            s->z[s->n] = z;
            s->n++;
        }
    }
    fclose(f);
    return s->n > 1 ? 0 : -1;
}

static double interp(const series *s, double t)
{
    if (t <= s->t[0])
        return s->z[0];
    for (int i = 1; i < s->n; i++)
        if (s->t[i] >= t) {
            double a = (t - s->t[i - 1]) / (s->t[i] - s->t[i - 1]);
            return s->z[i - 1] + a * (s->z[i] - s->z[i - 1]);
        }
    return s->z[s->n - 1];
}

/* profile at ~2.0 ms: direction (0 warp, 1 weft) → positions and values */
static int read_profile(const char *dir, int direction, double *pos, double *val, int max)
{
    char path[1024], line[512];
    snprintf(path, sizeof path, "%s/profiles.csv", dir);
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    int n = 0;
    while (n < max && fgets(line, sizeof line, f)) {
        double t, p, v;
        char d[16];
        if (sscanf(line, "%lf,%15[^,],%lf,%lf", &t, d, &p, &v) == 4 && fabs(t - 2.0e-3) < 2.5e-5 &&
            strcmp(d, direction ? "weft" : "warp") == 0) {
            pos[n] = p;
            val[n] = v;
            n++;
        }
    }
    fclose(f);
    return n;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: compare REFERENCE_DIR RUN_DIR\n");
        return 2;
    }
    series ref, run;
    if (read_history(argv[1], &ref) || read_history(argv[2], &run))
        return 1;
    double num = 0, den = 0, peak_ref = 0, peak_run = 0, tp_ref = 0, tp_run = 0;
    for (int i = 0; i < ref.n; i++) {
        if (ref.t[i] > 2.5e-3)
            break;
        double d = interp(&run, ref.t[i]) - ref.z[i];
        num += d * d;
        den += ref.z[i] * ref.z[i];
    }
    for (int i = 0; i < ref.n; i++)
        if (ref.z[i] > peak_ref) {
            peak_ref = ref.z[i];
            tp_ref = ref.t[i];
        }
    for (int i = 0; i < run.n; i++)
        if (run.z[i] > peak_run) {
            peak_run = run.z[i];
            tp_run = run.t[i];
        }
    static double pr[4096], vr[4096], pp[4096], vp[4096];
    double pnum = 0, pden = 0;
    for (int dir = 0; dir < 2; dir++) {
        int nr = read_profile(argv[1], dir, pr, vr, 4096), np = read_profile(argv[2], dir, pp, vp, 4096);
        for (int i = 0; i < nr && np > 1; i++) {
            double v = vp[np - 1];
            for (int j = 1; j < np; j++)
                if (pp[j] >= pr[i]) {
                    double a = (pr[i] - pp[j - 1]) / (pp[j] - pp[j - 1]);
                    v = vp[j - 1] + a * (vp[j] - vp[j - 1]);
                    break;
                }
            pnum += (v - vr[i]) * (v - vr[i]);
            pden += vr[i] * vr[i];
        }
    }
    printf("%.6g,%.6g,%.6g,%.6g\n", sqrt(num / den), (peak_run - peak_ref) / peak_ref,
           tp_run - tp_ref, pden > 0 ? sqrt(pnum / pden) : NAN);
    return 0;
}
