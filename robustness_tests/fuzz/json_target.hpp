#pragma once
// Shared by the JSON fuzz targets: the input goes through the readers' public entry points,
// which take a file (read_pairs_file, read_scene_file), so that the conversion of the JSON
// parser's errors into InputError is fuzzed too. Each process writes its inputs to one private
// temporary file; libFuzzer's -fork and -jobs workers each have their own.

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>

#include "rockcontact/dynamics/io/pairs_io.hpp"

namespace rockcontact::fuzz {

[[noreturn]] inline void fail(std::string_view target, std::string_view what) {
  std::fprintf(stderr, "%.*s: %.*s\n", static_cast<int>(target.size()), target.data(),
               static_cast<int>(what.size()), what.data());
  std::abort();
}

// A file that lives as long as the process (removed at exit).
class ScratchFile {
 public:
  explicit ScratchFile(std::string_view stem) {
    std::string pattern = (std::filesystem::temp_directory_path() / std::string(stem)).string() + ".XXXXXX";
    const int fd = mkstemp(pattern.data());
    if (fd < 0) fail(stem, "cannot create a temporary file");
    close(fd);
    path_ = pattern;
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  ~ScratchFile() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }

  const std::filesystem::path& write(std::span<const std::uint8_t> bytes) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) fail(path_.string(), "cannot write the temporary file");
    return path_;
  }

 private:
  std::filesystem::path path_;
};

// The documented error of both readers: a message "<source>: <path>: <problem>" (the path may
// be empty for the document as a whole), the source being the file it was given.
inline void check_input_error(std::string_view target, const dynamics::InputError& e,
                              const std::filesystem::path& file) {
  const std::string_view what = e.what();
  const std::string prefix = file.string() + ": ";
  if (e.source() != file.string() || what.substr(0, prefix.size()) != prefix || what.size() <= prefix.size()) {
    fail(target, "an InputError without the source, or without a problem: \"" + std::string(what) + "\"");
  }
}

// The scene targets' common course: the input read as a scene file (`read`); a reader error must
// be a documented InputError, any other exception fails; an accepted scene is checked
// (`check_accepted`) and, when `small`, run (`run`), whose exceptions other than the engine's
// documented ones (`run` catches those) fail with `engine_errors` named.
template <class Read, class Check, class Small, class Run>
int scene_input(std::string_view target, ScratchFile& scratch, std::span<const std::uint8_t> bytes, Read read,
                Check check_accepted, Small small, Run run, std::string_view engine_errors) {
  const std::filesystem::path& file = scratch.write(bytes);
  decltype(read(file)) scene;
  try {
    scene = read(file);
  } catch (const dynamics::InputError& e) {
    check_input_error(target, e, file);
    return 0;
  } catch (const std::exception& e) {
    fail(target, std::string("an exception other than InputError: ") + e.what());
  }
  check_accepted(scene);
  if (small(scene)) {
    try {
      run(scene);
    } catch (const std::exception& e) {
      fail(target, "the engine threw other than " + std::string(engine_errors) + ": " + e.what());
    }
  }
  return 0;
}

}  // namespace rockcontact::fuzz
