#!/bin/sh
# The option table (freefem_scripts/lib/wff_options.idp) on a scene of its own:
# defaults and typed values, the options JSON, -help, and every error class
# (unknown option, stray argument, missing value, a value that is an option,
# a duplicate, not a number, not a whole number, each check failing) stops
# with "error: SCENE: ..." naming the option and exit code 2.
set -u
tmp="${WFF_TEST_TMP:-/tmp}/options_table"
rm -rf "$tmp"; mkdir -p "$tmp"
cat > "$tmp/scene.edp" <<'EDP'
include "wovenff.idp"
wffOption("-tend", "3.0e-3", "s", "real>0", "end time");
wffOption("-dtfactor", "0.8", "", "real(0,2]", "fraction of the stable step");
wffOption("-ratio", "0.5", "", "real[0,1)", "a ratio");
wffOption("-mu", "0.3", "", "real>=0", "friction");
wffOption("-n", "1", "", "int>=1", "threads");
wffOption("-k", "0", "", "int", "any whole number");
wffOption("-plots", "1", "", "01", "draw pictures");
wffOption("-clamp", "fixed", "", "choice:fixed|friction", "clamp kind");
wffOption("-dirs", "warp,weft", "", "list:warp|weft|shear", "directions");
wffOption("-out", "results/x", "", "string", "results folder");
wffOptionsParse("opt_scene");
cout << "tend=" << wffOptReal("-tend") << " n=" << wffOptInt("-n") << " k=" << wffOptInt("-k")
     << " clamp=" << wffOptString("-clamp") << " dirs=" << wffOptString("-dirs")
     << " given_n=" << wffOptGiven("-n") << " given_mu=" << wffOptGiven("-mu") << endl;
cout << "json " << wffOptionsJson() << endl;
EDP
fail=0
# expect NAME STATUS PATTERN -- ARGS
expect() {
    name=$1; want=$2; pattern=$3; shift 4
    sh tools/ff.sh "$tmp/scene.edp" "$@" > "$tmp/$name.log" 2>&1
    rc=$?
    [ "$rc" -eq "$want" ] || { echo "$name: exit $rc, want $want"; sed 's/^/    | /' "$tmp/$name.log" | head -5; fail=1; }
    grep -qF -- "$pattern" "$tmp/$name.log" || { echo "$name: output lacks '$pattern'"; sed 's/^/    | /' "$tmp/$name.log" | head -5; fail=1; }
}
expect defaults 0 "tend=0.003 n=1 k=0 clamp=fixed dirs=warp,weft given_n=0 given_mu=0" --
expect json 0 'json {"tend": 0.003, "dtfactor": 0.8, "ratio": 0.5, "mu": 0.3, "n": 1, "k": 0, "plots": 1, "clamp": "fixed", "dirs": "warp,weft", "out": "results/x"}' --
expect given 0 "tend=0.002 n=3 k=-4 clamp=friction dirs=shear given_n=1 given_mu=0" \
    -- -tend 2e-3 -n 3 -k -4 -clamp friction -dirs shear
expect quoted_json 0 '"out": "a\"b"' -- -out 'a"b'
expect help 0 "-dtfactor       0.8" -- -help
expect help_1 0 "real(0,2]: fraction of the stable step" -- -help 1
expect unknown 2 "error: opt_scene: unknown option '-xyz' (known options: -tend -dtfactor -ratio" -- -xyz 1
expect stray 2 "error: opt_scene: unexpected argument 'coarse'" -- -tend 1 coarse
expect missing_value 2 "error: opt_scene: option -tend needs a value (real>0: end time)" -- -n 2 -tend
expect value_is_option 2 "error: opt_scene: option -out needs a value, not the option -tend" -- -out -tend 1
expect duplicate 2 "error: opt_scene: option -tend given twice ('1' and '2')" -- -tend 1 -tend 2
expect not_a_number 2 "error: opt_scene: -tend 'abc' is not a number (real>0) (end time, s)" -- -tend abc
expect not_strict 2 "error: opt_scene: -mu '1e' is not a number" -- -mu 1e
expect not_whole 2 "error: opt_scene: -n 1.5 is not a whole number (threads)" -- -n 1.5
expect greater 2 "error: opt_scene: -tend -1: must be > 0 (end time, s)" -- -tend -1
expect greater_zero 2 "error: opt_scene: -tend 0: must be > 0" -- -tend 0
expect at_least 2 "error: opt_scene: -n 0: must be >= 1 (threads)" -- -n 0
expect at_least_real 2 "error: opt_scene: -mu -0.1: must be >= 0 (friction)" -- -mu -0.1
expect open_low 2 "error: opt_scene: -dtfactor 0: must be in (0, 2]" -- -dtfactor 0
expect closed_high 0 "tend=0.003" -- -dtfactor 2
expect above_high 2 "error: opt_scene: -dtfactor 2.5: must be in (0, 2]" -- -dtfactor 2.5
expect open_high 2 "error: opt_scene: -ratio 1: must be in [0, 1)" -- -ratio 1
expect closed_low 0 "tend=0.003" -- -ratio 0
expect zero_one 2 "error: opt_scene: -plots 2: must be 0 or 1 (draw pictures)" -- -plots 2
expect choice 2 "error: opt_scene: -clamp 'glue': must be one of fixed|friction (clamp kind)" -- -clamp glue
expect list 2 "error: opt_scene: -dirs 'warp,foo': 'foo' is not one of warp|weft|shear" -- -dirs warp,foo
expect list_empty_item 2 "'' is not one of warp|weft|shear" -- -dirs warp,
exit $fail
