// Atomic writes (io/atomic_file.h): a writer killed in the middle leaves the previous output intact, and the next
// write of the same output removes the temporary the killed one left, and nothing else.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <set>
#include <string>

#include "io/atomic_file.h"
#include "core/errors.h"
#include "support/cli.h"
#include "support/datasets.h"

namespace vr {
namespace {
namespace fs = std::filesystem;

std::set<std::string> namesIn(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
    return names;
}

void write(const fs::path& path, const std::string& text) {
    writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

// Forks a writer of `path` that writes half its content, tells us, and waits; kills it with SIGKILL there.
// Returns its pid (reaped: it no longer exists).
pid_t killWriterMidway(const fs::path& path) {
    int ready[2];
    EXPECT_EQ(pipe(ready), 0);
    const pid_t child = fork();
    if (child == 0) {
        close(ready[0]);
        try {
            writeFileAtomically(path, [&](std::ostream& out) {
                out << std::string(100000, 'n');
                out.flush();
                (void)!::write(ready[1], "w", 1);
                pause();  // killed here, inside the write
            });
        } catch (...) {
        }
        _exit(3);
    }
    close(ready[1]);
    char byte = 0;
    EXPECT_EQ(read(ready[0], &byte, 1), 1) << "the writer ended before it wrote";
    close(ready[0]);
    kill(child, SIGKILL);
    int status = 0;
    EXPECT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    return child;
}

TEST(IoAtomicFile, KilledWriterLeavesThePreviousOutputAndTheNextWriteCleansUp) {
    const fs::path dir = test::scratchDir("atomic_file_killed");
    for (const auto& entry : fs::directory_iterator(dir)) fs::remove_all(entry.path());
    const fs::path out = dir / "image.png";
    write(out, "previous");
    const pid_t killed = killWriterMidway(out);

    EXPECT_EQ(test::slurp(out), "previous");
    std::set<std::string> names = namesIn(dir);
    ASSERT_EQ(names.size(), 2u);
    const std::string leftover = *std::next(names.begin(), names.begin()->starts_with(".image.tmp-") ? 0 : 1);
    EXPECT_TRUE(leftover.starts_with(".image.tmp-" + std::to_string(killed) + "-")) << leftover;
    EXPECT_TRUE(leftover.ends_with(".png")) << leftover;
    EXPECT_EQ(fs::file_size(dir / leftover), 100000u);

    // Files the next write must leave alone: another output's leftover, names near ours, and a temporary of a
    // live process (pid 1: init) written to just now.
    const std::vector<std::string> others{".other.tmp-" + std::to_string(killed) + "-0123abcd.png",
                                          ".image.tmp-" + std::to_string(killed) + "-0123abcd.jpg",
                                          ".image.tmp-" + std::to_string(killed) + "-0123abc.png",
                                          ".image.tmp-x" + std::to_string(killed) + "-0123abcd.png",
                                          "image.tmp-" + std::to_string(killed) + "-0123abcd.png",
                                          ".image.tmp-1-0123abcd.png"};
    for (const std::string& name : others) std::ofstream(dir / name) << "not ours to remove";
    // A live pid's temporary untouched for an hour is abandoned (its pid reused): removed.
    std::ofstream(dir / ".image.tmp-1-fedcba98.png") << "abandoned";
    fs::last_write_time(dir / ".image.tmp-1-fedcba98.png", fs::file_time_type::clock::now() - std::chrono::hours(1));

    write(out, "next");
    EXPECT_EQ(test::slurp(out), "next");
    std::set<std::string> expected(others.begin(), others.end());
    expected.insert("image.png");
    EXPECT_EQ(namesIn(dir), expected);
}

// The same for writers that need a path (OpenEXR's): the leftover of a killed one goes on the next write.
TEST(IoAtomicFile, PathWritersCleanUpToo) {
    const fs::path dir = test::scratchDir("atomic_file_path");
    for (const auto& entry : fs::directory_iterator(dir)) fs::remove_all(entry.path());
    const fs::path out = dir / "volume.vprep";
    write(out, "previous");
    killWriterMidway(out);
    EXPECT_EQ(namesIn(dir).size(), 2u);
    writePathAtomically(out, [](const fs::path& tmp) { std::ofstream(tmp) << "next"; });
    EXPECT_EQ(namesIn(dir), std::set<std::string>{"volume.vprep"});
    EXPECT_EQ(test::slurp(out), "next");
    // A failed write removes its own temporary and keeps the output.
    EXPECT_THROW(writePathAtomically(out, [&](const fs::path&) { throw InputError("refused"); }), InputError);
    EXPECT_EQ(namesIn(dir), std::set<std::string>{"volume.vprep"});
    EXPECT_EQ(test::slurp(out), "next");
}

// A file filled over a longer time (a movie, frame by frame): its output appears only on commit, and a writer that
// gives up on the way leaves the previous output and no temporary.
TEST(IoAtomicFile, PendingFileAppearsOnlyWhenCommitted) {
    const fs::path dir = test::scratchDir("atomic_file_pending");
    for (const auto& entry : fs::directory_iterator(dir)) fs::remove_all(entry.path());
    const fs::path out = dir / "orbit.gif";
    write(out, "previous");
    {
        PendingFile pending(out);
        std::ofstream(pending.temporary()) << "half of the frames";
        EXPECT_EQ(namesIn(dir).size(), 2u);
        EXPECT_EQ(test::slurp(out), "previous");
    }  // abandoned
    EXPECT_EQ(namesIn(dir), std::set<std::string>{"orbit.gif"});
    EXPECT_EQ(test::slurp(out), "previous");
    {
        PendingFile pending(out);
        EXPECT_THROW(pending.commit(), InputError);  // nothing written yet
        std::ofstream(pending.temporary()) << "every frame";
        pending.commit();
    }
    EXPECT_EQ(namesIn(dir), std::set<std::string>{"orbit.gif"});
    EXPECT_EQ(test::slurp(out), "every frame");
    EXPECT_THROW(PendingFile(dir / "absent" / "orbit.gif"), InputError);
}

}  // namespace
}  // namespace vr
