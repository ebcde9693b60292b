#pragma once
// gnuplot, the one way every stage draws a PNG. gnuplot is itself a small
// shell: it runs system("..."), substitutes `backquoted` text on command
// lines and expands @macros, so any text that comes from a scene (names,
// labels, paths) enters a script only through gnuplot_string().
#include <string>
#include <string_view>

#include "scene/process.hpp"

namespace scene {

// A gnuplot string literal that prints `text` and is never evaluated:
// single-quoted (gnuplot 5 substitutes neither `...` nor @macros inside
// single quotes, and a backslash there is an ordinary character), with
// every ' doubled. Control characters (a newline would end the command
// line) become spaces.
std::string gnuplot_string(std::string_view text);

// A file name for `plot`, `splot` or `set output`, as a literal that names
// the file and nothing else. A quoted name is not enough there: gnuplot
// reads '< cmd' as "run cmd and plot its output", '|cmd' as an output pipe,
// '$name' as a datablock and '-', '+', '++' as special files. Every
// relative path is therefore made to start with "./" (absolute paths start
// with '/'), then quoted as by gnuplot_string.
std::string gnuplot_path(std::string_view path);

// Runs gnuplot on the script file `script_path` with working directory
// `work_dir` (so the script names its data and output files relative to
// it), stdout and stderr to `log_path`. Paths relative to our own working
// directory are fine. RunError when gnuplot is missing or fails, naming
// the log and its last line.
ChildTimes run_gnuplot(const std::string& script_path, const std::string& work_dir,
                       const std::string& log_path);

}  // namespace scene
