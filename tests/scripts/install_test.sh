#!/usr/bin/env bash
# `cmake --install` into a fresh prefix: the binary runs and prints its build settings, the man
# pages exist and hold the flags of --help, the installed binary finds its installed plot scripts
# (it draws a space-time diagram), and the installed Python module imports and runs.
set -euo pipefail
build=$1
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
cmake --install "$build" --prefix "$prefix" > "$prefix/install.log" 2>&1 || { cat "$prefix/install.log"; fail "cmake --install"; }
"$prefix/bin/granchain" --version | grep -q "build type" || fail "--version prints no build settings"
for page in granchain granchain-run granchain-sweep granchain-reproduce granchain-analyze; do
  [ -s "$prefix/share/man/man1/$page.1" ] || fail "no man page $page.1"
done
grep -q "sample.-interval" "$prefix/share/man/man1/granchain-run.1" || fail "granchain-run.1 lacks the flags of run --help"
# Each subcommand's page has its own title and NAME line, and EXAMPLES and SEE ALSO sections.
for c in run theory collapse sweep merge export analyze trace reproduce; do
  page="$prefix/share/man/man1/granchain-$c.1"
  C=$(echo "$c" | tr a-z A-Z)
  grep -q "^\.TH GRANCHAIN-$C " "$page" || fail "granchain-$c.1 is not titled GRANCHAIN-$C"
  [ "$(sed -n '/^\.SH NAME/{n;s/ .*//;p;q}' "$page")" = "granchain-$c" ] || fail "granchain-$c.1: NAME is not granchain-$c"
  for section in EXAMPLES "SEE ALSO"; do
    grep -q "^\.SH \"\?$section" "$page" || fail "granchain-$c.1 lacks $section"
  done
done
[ -f "$prefix/share/granchain/plots/spacetime.py" ] || fail "plot scripts not installed"
# The installed binary draws with the installed scripts: move the source tree's plots out of
# sight by running from the prefix (the lookup prefers <prefix>/share/granchain/plots).
cd "$prefix"
"$prefix/bin/granchain" trace --N 3 --to 2 --output t.csv --plot t.png > /dev/null || fail "trace --plot with the installed binary"
[ -s t.png ] || fail "no figure drawn"
# The Python package goes where Debian's python3 looks for the same prefix: installed to
# /usr/local, `import granchain` works without PYTHONPATH.
pkg=$(ls -d "$prefix"/lib/python3*/dist-packages/granchain 2>/dev/null | head -1 || true)
if [ -n "$pkg" ]; then
  rel=${pkg#"$prefix"/}
  /usr/bin/python3 -c "import site, sys; sys.exit('/usr/local/${rel%/granchain}' not in site.getsitepackages())" \
    || fail "the module goes to <prefix>/${rel%/granchain}, which python3 does not search under /usr/local"
  (cd / && env -u PYTHONPATH PYTHONPATH="${pkg%/granchain}" /usr/bin/python3 -c "
import granchain
r = granchain.run(N=3, T=2, seed=1)
assert r['n_coll'] > 0, r
print('installed module:', granchain.__file__)" > /dev/null 2>&1) || fail "installed Python module"
fi
echo "install: binary, man pages, plot scripts and Python module OK"
