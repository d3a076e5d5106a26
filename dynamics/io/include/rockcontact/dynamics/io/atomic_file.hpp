#pragma once
// Output files that appear under their name only when they are complete.
//
// An AtomicFile writes to "NAME.partial" beside its target and renames it over NAME in
// commit(). A rename within one directory is atomic on POSIX file systems, so whoever opens
// NAME (a viewer, a script, the user after a full disk or an exception) finds the previous
// file or the whole new one, never a truncated one. A file that is not committed is removed
// when its AtomicFile is destroyed; after a hard kill only the ".partial" file is left, and
// its name says what it is.

#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>

namespace rockcontact::dynamics {

// An output file or directory that cannot be written; what() names it and says why.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class AtomicFile {
 public:
  // Opens TARGET.partial for writing (binary); throws OutputError if it cannot.
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&&) = delete;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  std::ostream& stream() { return out_; }
  const std::filesystem::path& target() const noexcept { return target_; }

  // Flushes, closes and renames the partial file over the target; throws OutputError when a
  // write or the rename failed (the partial file is then removed and the target untouched).
  void commit();

 private:
  void discard() noexcept;

  std::filesystem::path target_;
  std::filesystem::path partial_;
  std::ofstream out_;
  bool pending_ = true;
};

}  // namespace rockcontact::dynamics
