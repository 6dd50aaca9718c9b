// Bad input on the command line, one table: each row is a command, the exit code it must give,
// words its standard error must contain, and files of its folder that it must leave as they were.
// Rows that give exit code 2 must also print exactly one line, "granchain: error: ...", on
// standard error and nothing on standard output. Rows with exit code 0 are the cases next to the
// refused ones that must keep working.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace fs = std::filesystem;

namespace {

struct BadInputRow {
  // Arguments after `granchain`, as a shell reads them. It runs in a fresh copy of the prepared
  // folder (see prepare_folder), which is also its working folder; {dir} stands for that folder's path.
  std::string args;
  int exit_code;
  // Each must occur in standard error.
  std::vector<std::string> stderr_words;
  // Paths relative to the folder that must hold the same bytes afterwards; "*" means the whole
  // folder: no file added, removed or changed.
  std::vector<std::string> unchanged;
  // Each must occur in standard output.
  std::vector<std::string> stdout_words = {};
};

const std::vector<std::string> kAll = {"*"};

// clang-format off
const std::vector<BadInputRow> kRows = {
    // Ranges whose number of values cannot be represented or exceeds 100000 values per list, and
    // grids of more than 10^7 points, however large their product.
    {"sweep --e 0.1:0.9:1e-300 --dry-run", 2, {"--e = '0.1:0.9:1e-300'", "8e+299 values", "at most 100000 values"}, kAll},
    {"sweep --e 0.1:0.9:1e-10 --T 1 --dry-run", 2, {"--e", "8e+09 values", "at most 100000 values"}, kAll},
    {"sweep --k 1e4:1e8:x1.0000000000000002 --dry-run", 2, {"--k", "at most 100000 values", "a larger factor"}, kAll},
    {"sweep --k -1e308:1e308:1e-320 --dry-run", 2, {"--k", "too many values to count"}, kAll},
    {"sweep --N 1:60000:1,1:60000:1 --dry-run", 2, {"--N", "more than 100000 values", "in all"}, kAll},
    {"sweep --N 1:100000:1 --e 1e-5:1:1e-5 --T0 1:100000:1 --T 1:100000:1 --replicas 1000000 --dry-run", 2,
     {"1e+26 points", "--replicas", "at most 10000000"}, kAll},
    {"sweep --N 3 --T 1 --e 1e-300:1:x1e100 --dry-run", 0, {}, {"store.db"}, {"# 4 points"}},
    {"sweep --N 3 --T 1 --e 0.80:0.90:0.05 --dry-run", 0, {}, {"store.db"}, {"# 3 points"}},
    {"sweep --e 0.9:0.8:0.01 --dry-run", 2, {"--e", "first <= last"}, kAll},
    {"sweep --e 0.8:0.9 --dry-run", 2, {"--e", "not a value or a range"}, kAll},

    // Parameter files: only regular files, at most 1 MiB, read to the end without an error.
    {"run --config {dir}/adir --T 1 --db store.db", 2, {"--config", "is a directory", "at most 1 MiB"}, kAll},
    {"run --config /proc/self/mem --T 1", 2, {"--config", "'/proc/self/mem'", "cannot read"}, kAll},
    {"run --config /dev/zero --T 1", 2, {"--config", "'/dev/zero'", "character device", "1 MiB"}, kAll},
    {"run --config big.toml --T 1", 2, {"--config", "larger than 1 MiB"}, kAll},
    {"run --config missing.toml --T 1", 2, {"--config", "cannot read", "No such file"}, kAll},
    {"sweep --sweep adir --dry-run", 2, {"--sweep", "is a directory"}, kAll},
    {"sweep --sweep /dev/zero --dry-run", 2, {"--sweep", "character device"}, kAll},

    // A key set twice, in JSON (as written, or spelled with '_' and '-') as in TOML.
    {"run --config dup.json --T 1", 2, {"--config", "'dup.json'", "'N' is set twice"}, kAll},
    {"run --config dup_spelling.json --T 1", 2, {"--config", "'dt-factor' is set twice"}, kAll},
    {"sweep --sweep dup.json --dry-run", 2, {"--sweep", "'N' is set twice"}, kAll},
    {"run --config dup.toml --T 1", 2, {"--config", "'dup.toml' line 2", "redefine", "'N'"}, kAll},
    {"run --config table.toml --T 1", 2, {"--config", "'table.toml' line 1", "tables/sections are not supported"}, kAll},
    {"run --config date.toml --T 1", 2, {"--config", "'date.toml' line 2", "must be a number, a string or a list"}, kAll},
    {"run --config numbers.toml --no-db", 0, {}, kAll, {"k = 1e+06", "N = 3"}},
    {"run --config bad.json --T 1", 2, {"--config", "not valid JSON"}, kAll},
    {"run --config params.json --no-db", 0, {}, {"params.json", "store.db"}, {"N = 3"}},

    // --shard, --threads, --replicas: an empty value is given, and the whole value is quoted.
    {"sweep --shard '' --T 1 --dry-run", 2, {"--shard = ''", "1 <= i <= n <= 100000"}, kAll},
    {"sweep --shard 1/3/5 --T 1 --dry-run", 2, {"--shard = '1/3/5'"}, kAll},
    {"sweep --shard 3/2 --T 1 --dry-run", 2, {"--shard = '3/2'"}, kAll},
    {"sweep --threads '' --T 1 --dry-run", 2, {"--threads = ''", "1 <= threads <= 1024"}, kAll},
    {"sweep --replicas '' --T 1 --dry-run", 2, {"--replicas = ''"}, kAll},
    {"sweep --threads 0 --T 1 --dry-run", 2, {"--threads = '0'", "1 <= threads <= 1024"}, kAll},

    // reproduce takes --threads as sweep does.
    {"reproduce --threads 0 --db store.db", 2, {"--threads = '0'", "1 <= threads <= 1024"}, kAll},
    {"reproduce --threads 1025 --db store.db", 2, {"--threads = '1025'", "1 <= threads <= 1024"}, kAll},
    {"reproduce --threads '' --db store.db", 2, {"--threads = ''"}, kAll},

    // The TC time must reach the span of the hard engine's collapse watch.
    {"run --engine hard --tc 1e-12 --T 1 --db store.db", 2, {"--tc = 1e-12", "tc >= 1e-09"}, kAll},
    {"sweep --engine hard --tc 1e-12 --T 1 --dry-run", 2, {"--tc"}, kAll},
    {"run --engine hard --tc 1e-9 --N 3 --T 1 --no-db", 0, {}, kAll, {"engine hard"}},
    // The hard engine's soft start: hard engine only, a transient to run, a k the exact engine resolves.
    {"run --start-k 1e10 --T 1 --db store.db", 2, {"--start-k", "belongs to --engine hard"}, kAll},
    {"run --engine hard --start-k -1 --T 1 --db store.db", 2, {"--start-k = -1 is out of range", "start-k = 0 (off)"}, kAll},
    {"run --engine hard --start-k 1e10 --T 1 --transient 0 --db store.db", 2, {"--start-k = 1e10", "transient = 0", "--transient > 0"}, kAll},
    {"run --engine hard --start-k 1e60 --T 1 --db store.db", 2, {"--start-k = 1e60 is out of range", "0 < start-k <= ", "exact engine's clock"}, kAll},
    {"sweep --engine hard --start-k 1e60 --T 1 --dry-run", 2, {"--start-k = 1e60 is out of range"}, kAll},
    {"sweep --start-k 1e8 --T 1 --dry-run", 2, {"--start-k", "add hard to --engine"}, kAll},
    {"run --engine hard --drive sine --A 0.01 --omega 1e6 --start-k 1e6 --T 1 --db store.db", 2, {"--start-k = 1e6 is out of range", "start-k >= 1.2", "10 contact times"}, kAll},
    {"run --engine hard --start-k 1e8 --N 3 --T 1 --no-db", 0, {}, kAll, {"engine hard"}},
    // Drives: the plate's parameters belong to a plate, each given once, the sawtooth has no Gamma,
    // a plate needs its amplitude and frequency, its period at least 10 tau_c; the audit does not cover it.
    {"run --drive wobble --A 1 --omega 1 --engine reference --T 1 --db store.db", 2, {"--drive = 'wobble' is not a drive", "sine, sawtooth, quadratic"}, kAll},
    {"run --A 0.1 --T 1 --db store.db", 2, {"--A = 0.1 sets a vibrating plate", "--drive is thermal"}, kAll},
    {"sweep --Gamma 2 --T 1 --dry-run", 2, {"--Gamma = 2", "sets a vibrating plate"}, kAll},
    {"run --drive sine --A 0.1 --omega 2 --N 2 --T 1 --no-db --audit", 2, {"--audit", "does not cover a vibrating plate"}, kAll},
    {"run --drive quadratic --A 0.1 --omega 2 --N 2 --T 1 --no-db", 0, {}, kAll, {"drive: quadratic plate"}},
    {"run --drive sine --A 0.1 --Gamma 2 --omega 2 --engine reference --T 1 --db store.db", 2, {"--Gamma = 2", "one of --A, --Gamma"}, kAll},
    {"run --drive sine --A 0.1 --omega 2 --f 0.3 --engine reference --T 1 --db store.db", 2, {"--f = 0.3", "one of --omega, --f"}, kAll},
    {"run --drive sawtooth --Gamma 2 --omega 2 --engine reference --T 1 --db store.db", 2, {"--Gamma = 2", "sawtooth", "--A > 0"}, kAll},
    {"run --drive quadratic --Gamma 2 --engine reference --T 1 --db store.db", 2, {"needs the plate's frequency", "--omega > 0 or --f > 0"}, kAll},
    {"run --drive sine --omega 2 --engine reference --T 1 --db store.db", 2, {"needs the plate's amplitude", "--A > 0 or --Gamma > 0"}, kAll},
    {"run --drive sine --A -1 --omega 2 --engine reference --T 1 --db store.db", 2, {"--A = -1 is out of range", "A > 0"}, kAll},
    {"run --drive sine --A 0.1 --omega 1e4 --engine reference --T 1 --db store.db", 2, {"--omega = 1e4 is out of range", "10 contact times"}, kAll},
    {"run --drive sine --A 1e12 --omega 1 --engine reference --T 1 --db store.db", 2, {"--A = 1e12 is out of range", "height scale"}, kAll},
    {"run --drive sine --Gamma 2 --f 0.5 --N 2 --engine reference --T 1 --no-db", 0, {}, kAll, {"drive: sine plate"}},
    {"trace --setup free --drive sine --A 0.1 --omega 2 --engine reference -o t.csv", 2, {"--drive = 'sine'", "free space has no floor"}, kAll},

    // k, m, T, T0, g, d: a contact must last 1e6 clock resolutions, heights must resolve d.
    {"run --k 1e300", 2, {"--k = 1e300", "k <= 1.21e+44", "tau_c", "exact engine's clock"}, kAll},
    {"run --engine reference --k 1e300", 2, {"--k = 1e300", "k <= 1.49e+12", "tau_c", "reference engine's clock"}, kAll},
    {"run --engine reference-located --k 1e13 --N 3", 2, {"--k = 1e13", "k <= 1.49e+12"}, kAll},
    {"run --m 1e-300", 2, {"--m = 1e-300", "m >= ", "tau_c"}, kAll},
    {"run --engine hard --m 1e-300 --db {dir}/store.db", 2, {"--m = 1e-300", "m >= ", "height scale"}, kAll},
    {"run --T 1e20", 2, {"--T = 1e20", "transient + T <"}, kAll},
    {"run --T0 1e20", 2, {"--T0 = 1e20", "T0 <= "}, kAll},
    {"sweep --k 1e4,1e300 --T 1 --dry-run", 2, {"--k", "k <= "}, kAll},
    {"run --k 1e12 --N 3 --T 1 --no-db", 0, {}, kAll, {"k = 1e+12"}},
    {"run --k 1e20 --N 3 --T 1 --no-db", 0, {}, kAll, {"k = 1e+20"}},

    // An output that is one of the command's inputs (the same file, however named, existing or
    // about to be created) is refused before anything runs.
    {"run --N 2 --T 1 --db store.db --json store.db", 2, {"--json: 'store.db' is the same file as --db 'store.db'"}, kAll},
    {"run --N 2 --T 1 --db {dir}/store.db --json ./store.db", 2, {"--json", "is the same file as --db"}, kAll},
    {"run --N 2 --T 1 --db new.db --json new.db", 2, {"--json: 'new.db' is the same file as --db 'new.db'"}, kAll},
    {"run --config params.json --no-db --json params.json", 2, {"--json", "is the same file as --config"}, kAll},
    {"export --db store.db -o store.db", 2, {"--output: 'store.db' is the same file as --db"}, kAll},
    {"export --db store.db -o store.db --format json", 2, {"--output", "is the same file as --db"}, kAll},
    {"analyze --db store.db --json store.db", 2, {"--json: 'store.db' is the same file as --db"}, kAll},
    {"analyze --db store.db --plot store", 0, {}, {"store.db"}},
    {"collapse --N 3 --e 0.5 --k 1e4 --db store.db --json store.db", 2, {"--json", "is the same file as --db"}, kAll},
    {"collapse --N 3 --e 0.5 --k 1e4 --db store.db --events store.db", 2, {"--events", "is the same file as --db"}, kAll},
    {"trace --N 3 --to 1 --output t.csv --events t.csv", 2, {"--events: 't.csv' is the same file as --output"}, kAll},
    {"merge --into m.db params.json", 2, {"merge source: 'params.json'"}, kAll},

    // Every output against every input and every other output, whatever its flag: a store that is
    // the config or sweep file, figures whose names are computed (analyze --plot's panels, trace's
    // PDF beside its PNG, reproduce's files in --out), standard output where a file is needed.
    {"run --config params.json --db params.json", 2, {"--db: 'params.json' is the same file as --config 'params.json'"}, kAll},
    {"run --config empty.toml --db empty.toml --T 1", 2, {"--db: 'empty.toml' is the same file as --config"}, kAll},
    {"sweep --sweep sweep.toml --db sweep.toml --T 1", 2, {"--db: 'sweep.toml' is the same file as --sweep"}, kAll},
    {"analyze --db q_N2_T01_exact.png --plot q", 2, {"--plot: 'q_N2_T01_exact.png' is the same file as --db"}, kAll},
    {"analyze --db curve.db --plot r --json r_N2_T01_exact.pdf", 2, {"--plot: 'r_N2_T01_exact.pdf' is the same file as --json"}, kAll},
    {"trace --N 3 --to 1 --output t.pdf --plot t.png", 2, {"--plot (its PDF): 't.pdf' is the same file as --output"}, kAll},
    {"trace --N 3 --to 1 --output t.csv --plot t.svg", 2, {"--plot: 't.svg' must name a PNG file"}, kAll},
    {"trace --N 3 --to 1 --output -", 2, {"--output: '-' (standard output) is not possible"}, kAll},
    {"collapse --N 3 --e 0.5 --k 1e4 --events - --no-db", 2, {"--events: '-' (standard output) is not possible"}, kAll},
    {"reproduce --figure fig1 --db out/fig1-trace.csv --out out", 2, {"--db: 'out/fig1-trace.csv' lies in --out 'out'"}, kAll},
    {"merge --into '' store.db", 2, {"--into: the file name is empty"}, kAll},
    {"run --N 2 --T 1 --db ''", 2, {"--db: the path is empty"}, kAll},

    // A store that lacks a column or a table is named as damaged, by every command that reads it.
    {"analyze --db nobins.db", 2, {"--db: 'nobins.db' is damaged", "the column 'bins' of the table 'runs'"}, kAll},
    {"export --db noprofiles.db", 2, {"--db: 'noprofiles.db' is damaged", "the table 'profiles'"}, kAll},
    {"merge --into m.db nobins.db", 2, {"merge source: 'nobins.db' is damaged"}, kAll},

    // Numbers beyond a double, integers beyond 64 bits: out of range, with the range, not "not a number".
    {"run --e 1e309", 2, {"--e = '1e309' is out of range: larger than the largest double", "0 < e <= 1"}, kAll},
    {"run --k 1e-400", 2, {"--k = '1e-400' is out of range: smaller than the least positive double"}, kAll},
    {"run --seed 9223372036854775808", 2, {"--seed = '9223372036854775808' is out of range"}, kAll},
    {"sweep --e 1e309 --dry-run", 2, {"--e", "is out of range: beyond the range of a double"}, kAll},
    {"run --config huge.json", 2, {"--config: 'huge.json' holds a number out of range"}, kAll},
    {"sweep --sweep huge.json --dry-run", 2, {"--sweep: 'huge.json' holds a number out of range"}, kAll},

    // Ranges that hold in every command: collapse's k against its clock, its integers parsed as run's.
    {"collapse --N 3 --e 0.05 --k 1e300 --no-db", 2, {"--k: 1e+300 is out of range", "1e6 times the engine's clock resolution"}, kAll},
    {"collapse --engine reference --N 3 --e 0.05 --k 1e4:1e20:x100 --no-db", 2, {"--k: 1e+18 is out of range"}, kAll},
    {"collapse --N 3 --e 0.05 --k 1e4:1e60:x1e4 --no-db", 2, {"--k: 1e+52 is out of range"}, kAll},
    {"collapse --threads 0 --no-db", 2, {"--threads = '0'", "1 <= threads <= 1024"}, kAll},
    {"collapse --seed 18446744073709551616 --no-db", 2, {"--seed = '18446744073709551616'", "9223372036854775807"}, kAll},
    {"collapse --N 010 --e 0.5 --k 1e4 --realizations 4 --no-db", 0, {}, kAll, {"N = 10,"}},  // decimal, as run reads it
    {"collapse --N 3 --e 0.05 --k 1e4 --realizations 4 --threads 1 --no-db -q", 0, {}, kAll},

    // Profile samples: 16 to 1e10 per window, at times the clock resolves; never a run without end.
    {"run --N 5 --T 5 --sample-interval 1e-20", 2, {"--sample-interval = 1e-20 is out of range", "16 to 1e10 profile samples"}, kAll},
    {"run --N 5 --T 1 --sample-interval 1e-17", 2, {"--sample-interval = 1e-17 is out of range"}, kAll},
    {"run --N 5 --T 0.1", 2, {"--T = 0.1 is out of range", "16 sample-intervals <= T"}, kAll},
    {"run --engine hard --N 5 --T 1e5 --transient 1e9 --sample-interval 1e-3", 2, {"--sample-interval = 1e-3 is out of range", "clock's resolution"}, kAll},

    // Limits that keep every run finite: the clock, the histograms' memory, the progress period,
    // trace's window against its clock, an error bar for every count.
    {"run --N 100000 --T 1", 2, {"--N = 100000 is out of range", "N <= 43690 at bins = 1024", "1 GiB"}, kAll},
    {"run --engine hard --N 3 --T 1 --transient 1e16", 2, {"--transient = 1e16 is out of range", "transient + T <= 1e15"}, kAll},
    {"trace --N 3 --from 1e10 --to 1.0000001e10 --dt 1e-9", 2, {"--dt = 1e-09 is out of range", "clock's resolution"}, kAll},
    {"trace --N 3 --setup free --v0 inf --to 1", 2, {"--v0 = 'inf' is not finite; valid range: v0 > 0"}, kAll},
    {"sweep --progress-every 1e300 --T 1 --dry-run", 2, {"--progress-every", "0.1 <= seconds <= 86400"}, kAll},
    {"collapse --realizations 1 --no-db", 2, {"--realizations = '1'", "2 <= realizations"}, kAll},
    {"analyze --db store.db --k-min inf", 2, {"--k-min = inf is out of range", "finite"}, kAll},
    {"export --db empty.toml", 2, {"--db: 'empty.toml' is empty"}, kAll},
    {"merge --into m.db empty.toml", 2, {"merge source: 'empty.toml' is empty"}, kAll},
    {"collapse --engine hard --N 3 --e 0.05 --a 1e8 --no-db", 2, {"--a = 1e+08", "launch's time scale", "<= 1e6"}, kAll},
    {"collapse --engine hard --N 3 --e 0.05 --tc 1e-30 --no-db", 2, {"--tc = 1e-30 is out of range", "tc >= collapse-time"}, kAll},
    {"collapse --N 3 --e 0.05 --k 1e4 --collapse-time 1e-6 --no-db", 2, {"the collapse watch belongs to --engine hard"}, kAll},
    {"run --config float_n.json --no-db", 2, {"--N = '3.0'", "is not an integer"}, kAll},
    {"export --db store.db --e 0.001:0.999:0.001", 2, {"--e: 999 values in one filter", "at most 500"}, kAll},
    {"collapse --engine hard --collapse-collisions 1000000000 --no-db", 2, {"--collapse-collisions = '1000000000'", "10000000"}, kAll},
    {"collapse --e 0.01:0.99:0.01 --k 1e4:1e10:x10 --realizations 10000000 --no-db", 2, {"at most 1e9 launches"}, kAll},
    {"export --db store.db --where \"json_extract(result_json, '$[') > 0\"", 2, {"--where"}, kAll},
    // CLI11's words in granchain's: the flag and the value as given.
    {"collapse --a abc --no-db", 2, {"--a = 'abc' is not a number"}, kAll},
    {"collapse --N 3 --N 4 --no-db", 2, {"--N is given more than once"}, kAll},
    {"merge --into m.db", 2, {"merge: name at least one source store"}, kAll},

    // A command that is not one: the list of commands.
    {"nosuch", 2, {"'nosuch' is not a command; commands: run, theory"}, kAll},
    {"", 2, {"name a command first; commands: run"}, kAll},

    // --out of reproduce: a folder; --print-sweeps writes nothing.
    {"reproduce --figure fig1 --db store.db --out params.json", 2, {"--out: 'params.json' is a file, not a folder"}, kAll},
    {"reproduce --figure fig1 --db store.db --out /proc/x", 2, {"--out: cannot create the folder '/proc/x'"}, kAll},
    {"reproduce --figure fig5 --db store.db --out figs --print-sweeps", 0, {}, kAll, {"granchain sweep"}},

    // Write errors are exit 4 and say what was kept: a JSON that cannot be written leaves the run
    // unstored; a device that refuses the bytes (after the run is stored) says that it is stored.
    {"run --N 2 --T 1 --db store.db --json /proc/out.json", 4, {"--json: cannot write '/proc/out.json'", "nothing was stored or written"},
     {"store.db"}},
    {"run --N 2 --T 1 --db store.db --json /dev/full", 4, {"--json: cannot write '/dev/full': No space left on device", "the run is stored"}, {}},
    {"run --N 2 --T 1 --no-db --json /dev/full", 4, {"--json: cannot write '/dev/full'"}, kAll},
    {"export --db store.db -o /dev/full", 4, {"--output: cannot write '/dev/full': No space left on device"}, kAll},
    {"analyze --db store.db --json /dev/full", 4, {"--json: cannot write '/dev/full'"}, kAll},
    {"theory --N 3 --json /dev/full", 4, {"--json: cannot write '/dev/full'"}, kAll},
    {"trace --N 3 --to 1 --output /dev/full", 4, {"--output: cannot write '/dev/full'"}, kAll},

    // Bad input that was refused before.
    {"run --N 0 --db store.db", 2, {"--N", "1 <= N <= 100000"}, kAll},
    {"run --e 1.5", 2, {"--e", "0 < e <= 1"}, kAll},
    {"run --bogus 1", 2, {"--bogus"}, kAll},
    {"swep --N 3", 2, {"'swep' is not a command; did you mean 'sweep'?"}, kAll},
    {"run --NN 3", 2, {"--NN is not a flag of run; did you mean --N?"}, kAll},
    {"sweep --tread 2 --dry-run", 2, {"did you mean --threads?"}, kAll},
    {"run --k 1e4x", 2, {"--k", "not a number"}, kAll},
};
// clang-format on

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Every regular file under `root` (relative path -> bytes); directories as entries with "<dir>".
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string rel = fs::relative(entry.path(), root).string();
    files[rel] = entry.is_regular_file() ? slurp(entry.path()) : "<" + rel + ">";
  }
  return files;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

int run_shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The files every row finds in its folder.
void prepare_folder(const fs::path& dir) {
  fs::create_directories(dir / "adir");
  const auto write = [&](const std::string& name, const std::string& text) { std::ofstream(dir / name, std::ios::binary) << text; };
  write("params.json", "{\"N\": 3, \"T\": 1, \"transient\": 0.1}");
  write("dup.json", "{\"N\": 5, \"N\": 6}");
  write("dup_spelling.json", "{\"dt_factor\": 100, \"dt-factor\": 200}");
  write("dup.toml", "N = 5\nN = 6\n");
  write("table.toml", "[run]\nN = 3\n");
  write("date.toml", "N = 3\nstart = 1979-05-27\n");
  write("numbers.toml", "N = 3\nk = 1_000_000  # every TOML number\nT = 1.0\ntransient = 1e-1\n");
  write("bad.json", "{\"N\": 5, \"e\": ");
  write("huge.json", "{\"e\": 1e400}");
  write("float_n.json", "{\"N\": 3.0, \"T\": 1}");
  write("empty.toml", "");
  write("sweep.toml", "N = 3\n");
  write("big.toml", "N = 3\n" + std::string(std::size_t{1} << 20, '#') + "\n");
  // A results store holding one run.
  const int code = run_shell("cd '" + dir.string() + "' && '" GRANCHAIN_BINARY "' run --N 2 --T 1 --transient 0 --quiet --db store.db");
  ASSERT_EQ(code, 0) << "could not make the store";
  ASSERT_TRUE(fs::exists(dir / "store.db"));
  // A store with one curve n_coll(k), and a copy under the name of analyze --plot q's panel; copies
  // of the first, damaged (a column, a table gone).
  ASSERT_EQ(run_shell("cd '" + dir.string() + "' && '" GRANCHAIN_BINARY "' sweep --N 2 --e 0.5 --k 1e4,1e5,1e6 --T 20 --transient 0 -q --db curve.db"), 0);
  fs::copy_file(dir / "curve.db", dir / "q_N2_T01_exact.png");
  fs::copy_file(dir / "store.db", dir / "nobins.db");
  fs::copy_file(dir / "store.db", dir / "noprofiles.db");
  fs::create_directories(dir / "out");
  fs::copy_file(dir / "store.db", dir / "out" / "fig1-trace.csv");
  ASSERT_EQ(run_shell("sqlite3 '" + (dir / "nobins.db").string() + "' 'ALTER TABLE runs DROP COLUMN bins'"), 0);
  ASSERT_EQ(run_shell("sqlite3 '" + (dir / "noprofiles.db").string() + "' 'DROP TABLE profiles'"), 0);
}

}  // namespace

TEST(BadInput, EveryRowOfTheTable) {
  TempDir tmp;
  const fs::path prepared = tmp.path / "prepared";
  prepare_folder(prepared);
  if (HasFatalFailure()) return;
  for (std::size_t i = 0; i < kRows.size(); ++i) {
    const BadInputRow& row = kRows[i];
    const fs::path dir = tmp.path / ("row" + std::to_string(i));
    fs::copy(prepared, dir, fs::copy_options::recursive);
    const auto before = snapshot(dir);
    const std::string args = replace_all(row.args, "{dir}", dir.string());
    // At most 60 s and 4 GiB of address space, so that a regression (a file read without end)
    // fails this test instead of the machine.
    const int code = run_shell("cd '" + dir.string() + "' && ulimit -v 4194304 && timeout 60 '" GRANCHAIN_BINARY "' " + args +
                               " > '" + (tmp.path / "stdout.txt").string() + "' 2> '" + (tmp.path / "stderr.txt").string() + "'");
    const std::string out = slurp(tmp.path / "stdout.txt");
    const std::string err = slurp(tmp.path / "stderr.txt");
    SCOPED_TRACE("row " + std::to_string(i) + ": granchain " + args + "\nstderr: " + err);
    EXPECT_EQ(code, row.exit_code);
    for (const auto& w : row.stderr_words) EXPECT_TRUE(err.find(w) != std::string::npos) << "stderr lacks: " << w;
    for (const auto& w : row.stdout_words) EXPECT_TRUE(out.find(w) != std::string::npos) << "stdout lacks: " << w;
    if (row.exit_code == 2) {
      EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1);
      EXPECT_EQ(err.rfind("granchain: error: ", 0), 0u);
      EXPECT_TRUE(out.empty()) << out;
    }
    const auto after = snapshot(dir);
    for (const auto& name : row.unchanged) {
      if (name == "*") {
        for (const auto& [file, bytes] : before) {
          const auto it = after.find(file);
          EXPECT_TRUE(it != after.end() && it->second == bytes) << file << " was changed or removed";
        }
        for (const auto& [file, bytes] : after) EXPECT_TRUE(before.count(file)) << file << " was written";
      } else {
        ASSERT_TRUE(before.count(name)) << name << " is not a prepared file";
        const auto it = after.find(name);
        EXPECT_TRUE(it != after.end() && it->second == before.at(name)) << name << " was changed or removed";
      }
    }
    fs::remove_all(dir);
  }
}
