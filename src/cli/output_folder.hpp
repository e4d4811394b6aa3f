#pragma once
// Who owns an output folder, and what a run may touch in it (docs/contract.md,
// "The output folder"):
// - A run owns its folder for as long as it runs: an advisory lock
//   (flock) on `.sphclip.lock` inside it, held until the process ends. A
//   second run into the same folder is refused (exit 2) naming the folder and
//   the holder's pid; two runs never mix their files.
// - sphclip writes only its own names there (frames/, particles/,
//   stats.csv, run.json, clip.mp4, particles.pvd, and their ".partial"
//   temporaries), and never through a symbolic link: a link, or an entry of
//   the wrong type (a file named frames, a folder named run.json), is
//   refused before anything is written.
// - A folder that an earlier sphclip run wrote (its run.json says so) is
//   taken over: that run's outputs are removed first, all of them, so none
//   of them outlives the new run. A folder that holds a file of one of
//   those names that no sphclip run wrote is refused: nothing a user made
//   is removed or overwritten.

#include <filesystem>
#include <string>
#include <vector>

namespace sph {

class OutputFolder {
  public:
    // Creates `folder` if needed, takes its lock, checks every name a run
    // writes and removes an earlier run's outputs. Throws InputError (exit
    // 2) when the folder cannot be used; nothing in it is changed then.
    explicit OutputFolder(std::filesystem::path folder);
    ~OutputFolder();
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;

    const std::filesystem::path& path() const { return folder_; }
    // The earlier run's outputs that were removed, by name ("frames/ (31
    // files)", "clip.mp4"), to tell the user; empty for a fresh folder.
    const std::vector<std::string>& replaced() const { return replaced_; }

  private:
    std::filesystem::path folder_;
    int lock_fd_ = -1;
    std::vector<std::string> replaced_;
};

} // namespace sph
