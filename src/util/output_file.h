// Every file shadetwin writes (EXR, PNG, CSV, plots, device descriptions) goes through OutputFile: it is written under a
// temporary name in its destination folder and renamed into place when complete, so a reader never sees a partial file
// and a failed or interrupted write never destroys the previous result (issue 20, item 4).
#pragma once

#include <fstream>
#include <string>

namespace shadetwin {

class OutputFile {
 public:
  /// Throws FileError (util/image_io.h) naming `path` when its folder does not exist or cannot be written.
  explicit OutputFile(std::string path);
  ~OutputFile();  // removes the temporary unless commit() succeeded
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  const std::string& path() const { return path_; }
  /// The temporary's name, for writers that take a path (OpenImageIO): "<dir>/.tmp-<pid>-<n>-<name>" (same extension).
  const std::string& tempPath() const { return temp_; }
  /// A text stream onto the temporary, opened on first use.
  std::ostream& stream();
  /// Closes the stream (if used), checks it, renames the temporary into place. Throws FileError naming the path.
  void commit();

 private:
  std::string path_, temp_;
  std::ofstream out_;
  int slot_ = -1;
  bool committed_ = false;
};

/// Throws FileError naming `path` when it cannot be written: its folder is missing or not writable, or it is a folder.
/// Commands call it on their outputs before the work (nothing is computed for an output that cannot be written).
void checkWritable(const std::string& path);

/// SIGINT and SIGTERM remove every live OutputFile temporary, then end the process by the signal (exit status 128 + n
/// from a shell). Idempotent; the CLI calls it first thing.
void installInterruptCleanup();

/// The temporaries alive now (for tests).
int liveOutputTemporaries();

}  // namespace shadetwin
