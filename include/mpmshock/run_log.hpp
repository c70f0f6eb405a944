// log.txt: what a run prints (warnings, progress lines, the stop message, errors, the summary)
// goes to the terminal as before and, once output_dir is prepared, into output_dir/log.txt, which
// opens with the run's provenance. Lines said before the directory exists are kept and written
// first. Only the rank that speaks (rank 0) calls these; nothing logs before main records the
// invocation.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

namespace mpmshock {

// Prints `text` on `stream` (stdout or stderr) and keeps it for log.txt.
void say(std::FILE* stream, const std::string& text);
// Keeps `text` for log.txt only (the progress line, which the terminal redraws in place).
void log_only(const std::string& text);
// Opens dir/log.txt: a new run writes it afresh, a restart that goes on in the run's directory
// appends (`continued`). Writes the provenance header and every line said so far.
void open_run_log(const std::filesystem::path& dir, bool continued);

}  // namespace mpmshock
