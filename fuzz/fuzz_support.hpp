// hotmesh fuzz: what the libFuzzer targets share (docs/fuzzing.md). A target feeds one input
// to one reader of user input as the program does; the reader may refuse it only in the
// documented way, with hotmesh::InputError (the service: ApiError), whose message names the
// input. Anything else escapes the target and libFuzzer reports it as a crash: a signal, a
// sanitizer report, an exception of another type (the program's exit 3 or HTTP 500), a
// message that does not name the file.
#pragma once

#include <sanitizer/lsan_interface.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace hotmesh::fuzz {

/// The fuzzer's input as text.
inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// A folder of this process for the files a target writes, empty when first asked for and
/// removed at exit: <build>/fuzz/work/<pid>.
const std::filesystem::path& work_folder();

/// A folder of this process in memory, /dev/shm/hotmesh-fuzz/<pid> (below work_folder() where
/// there is no /dev/shm), empty when first asked for and removed at exit: for targets that
/// write their input as files at every execution, which on the build's disk costs a
/// millisecond each (the file system discards the blocks a truncation frees).
const std::filesystem::path& memory_folder();

/// Writes `content` to `file` (replacing it).
void write_bytes(const std::filesystem::path& file, std::string_view content);

/// A file of the source tree, named from its top (samples/ramp2d/ramp2d.msh).
std::filesystem::path source_file(std::string_view relative);

/// Points the process's temporary folder (TMPDIR), where the service makes its private
/// folder for uploads, at an empty folder of this process, and returns it.
std::filesystem::path use_private_temporary_folder();

/// Aborts if a regular file is left anywhere below `folder`: the service removes every upload
/// once read, and whenever a request fails.
void require_no_files_left(const std::filesystem::path& folder);

/// While alive, what this thread allocates is not reported as a leak. For OpenCASCADE's STEP
/// and IGES readers, which keep process-wide registries made on first use and, by design,
/// abandon the objects of a translation that faulted (OCC_CATCH_SIGNALS) or a parse that
/// stopped on a bad IGES record: leaks of a third-party library on every damaged file, which
/// LeakSanitizer could tell from hotmesh's only with full stacks (fast_unwind_on_malloc=0, as
/// tests/lsan.supp needs), at a large cost in executions. The ASan test suite checks these
/// paths for leaks of hotmesh's own code.
using OcctLeaksIgnored = __lsan::ScopedDisabler;

/// Aborts (a crash for libFuzzer) unless `message` names `source`: every refusal of user
/// input says which file or field is wrong.
void require_named(std::string_view message, std::string_view source);

}  // namespace hotmesh::fuzz
