// Output files (apps/image/output_files.hpp): all or nothing, through symbolic links, never
// over a non-regular file, permissions kept, and nothing left behind, also when the process
// is interrupted by a signal (issue 17, items 8-10); several writers of one file at once,
// killed writers, streams and dangling links (issue 32, items 1, 5 and 10). In-process, and
// through `penumbra`.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_runner.hpp"
#include "image/output_files.hpp"
#include "image/png_io.hpp"

namespace fs = std::filesystem;

namespace {

using Outputs = penumbra::testing::CliTest;

std::string read_all(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// The temporaries of `target` in its folder, of any process.
int temporaries_of(const fs::path& target) {
    int count = 0;
    for (const auto& entry : fs::directory_iterator(target.parent_path())) {
        count += penumbra::is_temporary_of(target, entry.path().filename().string());
    }
    return count;
}

// Each signal that ends a process while a set is half written: the temporaries go, and the
// folders the set created, and the process still dies of that signal.
TEST_F(Outputs, TemporariesAreRemovedWhenTheProcessIsSignalled) {
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
        const fs::path a = dir_ / "made" / "deeper" / "a.png";
        const fs::path b = dir_ / "b.json";
        const pid_t child = fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            const rlimit no_core{0, 0};
            setrlimit(RLIMIT_CORE, &no_core);     // SIGQUIT's default action dumps core
            std::signal(signal_number, SIG_DFL);  // a background shell's job ignores SIGINT and SIGQUIT
            penumbra::OutputFiles output({a, b}, penumbra::OutputFolders::MayBeCreated);
            output.write(a, "first file");
            std::raise(signal_number);
            _exit(0);  // not reached
        }
        int status = 0;
        ASSERT_EQ(waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal_number) << signal_number << ": " << status;
        EXPECT_FALSE(fs::exists(dir_ / "made")) << signal_number;
        EXPECT_FALSE(fs::exists(b)) << signal_number;
        EXPECT_EQ(temporaries_of(b), 0) << signal_number;
    }
}

// A set that fails leaves no folder it created (compare's --out-dir), and none it did not.
TEST_F(Outputs, AFailedSetRemovesTheFoldersItCreated) {
    fs::create_directory(dir_ / "existing");
    {
        penumbra::OutputFiles output({dir_ / "existing" / "new" / "a.png"}, penumbra::OutputFolders::MayBeCreated);
        output.write(dir_ / "existing" / "new" / "a.png", "A");
        EXPECT_TRUE(fs::exists(dir_ / "existing" / "new"));
    }  // abandoned: a failure before commit()
    EXPECT_FALSE(fs::exists(dir_ / "existing" / "new"));
    EXPECT_TRUE(fs::exists(dir_ / "existing"));
}

// Two writers of one file in one process: neither removes the other's temporary, and each
// commit puts its own bytes in place whole.
TEST_F(Outputs, TwoWritersOfOneFileKeepTheirOwnTemporaries) {
    const fs::path out = dir_ / "out.png";
    penumbra::OutputFiles first({out});
    first.write(out, "first writer");
    {
        penumbra::OutputFiles second({out});
        second.write(out, "second writer");
        EXPECT_EQ(temporaries_of(out), 2);
        second.commit();
    }
    EXPECT_EQ(read_all(out), "second writer");
    first.commit();
    EXPECT_EQ(read_all(out), "first writer");
    EXPECT_EQ(temporaries_of(out), 0);
}

// A writer in another process that is alive (here: waiting in the middle of its set) keeps
// its temporary while this process writes the same file, then commits its own bytes.
TEST_F(Outputs, ALiveWritersTemporaryIsNeverRemoved) {
    const fs::path out = dir_ / "out.png";
    int ready[2];
    int go[2];
    ASSERT_EQ(pipe(ready), 0);
    ASSERT_EQ(pipe(go), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        penumbra::OutputFiles output({out});
        output.write(out, "the other process");
        char byte = 'r';
        if (::write(ready[1], &byte, 1) != 1 || ::read(go[0], &byte, 1) != 1) _exit(3);
        output.commit();
        _exit(0);
    }
    char byte = 0;
    ASSERT_EQ(::read(ready[0], &byte, 1), 1);
    penumbra::write_output_file(out, "this process");
    EXPECT_EQ(temporaries_of(out), 1);  // the other process's, untouched
    ASSERT_EQ(::write(go[1], &byte, 1), 1);
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
    EXPECT_EQ(read_all(out), "the other process");
    EXPECT_EQ(temporaries_of(out), 0);
    for (const int descriptor : {ready[0], ready[1], go[0], go[1]}) ::close(descriptor);
}

// A writer killed outright leaves its temporary; the next writer of that file removes it.
TEST_F(Outputs, AKilledWritersTemporaryIsRemovedByTheNextWriter) {
    const fs::path out = dir_ / "out.png";
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        penumbra::OutputFiles output({out});
        output.write(out, "killed half way");
        std::raise(SIGKILL);
        _exit(0);  // not reached
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << status;
    EXPECT_EQ(temporaries_of(out), 1);
    EXPECT_FALSE(fs::exists(out));
    penumbra::write_output_file(out, "next run");
    EXPECT_EQ(temporaries_of(out), 0);
    EXPECT_EQ(read_all(out), "next run");
}

// Two `penumbra render` runs to one -o at once: both succeed, and the file is one of their
// images, whole.
TEST_F(Outputs, ConcurrentRendersToOneOutputBothWriteAWholeImage) {
    const std::string render =
        "'" + std::string(penumbra::testing::penumbra_binary()) + "' render builtin:default -o out.png ";
    const std::string both = "cd '" + dir_.string() + "' && (" + render + "--width 32 --height 18 > a.txt 2>&1 & " +
                             render + "--width 48 --height 27 > b.txt 2>&1; b=$?; wait $!; a=$?; exit $((a | b)))";
    const int status = std::system(both.c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << penumbra::testing::read_text(dir_ / "a.txt") << penumbra::testing::read_text(dir_ / "b.txt");
    const penumbra::PngImage image = penumbra::read_png(dir_ / "out.png");
    EXPECT_TRUE((image.width == 32u && image.height == 18u) || (image.width == 48u && image.height == 27u))
        << image.width << "x" << image.height;
    EXPECT_EQ(temporaries_of(dir_ / "out.png"), 0);
}

// A stream is refused even when it is a regular file underneath (stdout redirected to one);
// a dangling symbolic link is written through, creating its target, as cp does.
TEST_F(Outputs, StreamsAreRefusedAndDanglingLinksWrittenThrough) {
    const std::string small = "render builtin:default --width 32 --height 18 ";
    const penumbra::testing::RunResult stream = run(small + "-o /dev/stdout");
    expect_failure(stream, 2, "/dev/stdout: names a stream or device");
    EXPECT_TRUE(fs::is_regular_file(dir_ / "stdout.txt"));  // the redirected file, not replaced
    EXPECT_TRUE(stream.out.empty());

    fs::create_symlink("made.png", dir_ / "dangling.png");
    ASSERT_EQ(run(small + "-o dangling.png").exit_code, 0);
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "dangling.png")));
    EXPECT_EQ(penumbra::read_png(dir_ / "made.png").width, 32u);
}

// A name longer than the file system allows fails before the device is even chosen (an
// unknown --device would exit 3); a long name that fits is written (its temporary's name is
// shortened to fit).
TEST_F(Outputs, NameLengthsAreCheckedBeforeRendering) {
    const std::string too_long(300, 'n');
    expect_failure(run("render builtin:default --device no-such-device -o " + too_long + ".png"), 2,
                   "the file name is 304 bytes long, more than the 255 its file system allows");
    const std::string long_name = std::string(246, 'n') + ".png";
    ASSERT_EQ(run("render builtin:default --width 32 --height 18 -o " + long_name).exit_code, 0);
    EXPECT_EQ(penumbra::read_png(dir_ / long_name).width, 32u);
    EXPECT_EQ(temporaries_of(dir_ / long_name), 0);
}

// An empty --out-dir is refused (it would have put seven files into the current folder).
TEST_F(Outputs, CompareRefusesAnEmptyOutDir) {
    expect_failure(run("compare builtin:default --width 32 --height 18 --out-dir ''"), 2, "--out-dir: empty");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2);  // stdout.txt, stderr.txt
}

// Nothing of a set is in place until every file of it is written.
TEST_F(Outputs, ASetIsWrittenAllOrNothing) {
    const fs::path a = dir_ / "a.txt";
    const fs::path b = dir_ / "b.txt";
    {
        penumbra::OutputFiles output({a, b});
        output.write(a, "A");
        EXPECT_FALSE(fs::exists(a));  // still a temporary
    }                                 // abandoned: a failure before commit()
    EXPECT_FALSE(fs::exists(a));
    EXPECT_EQ(temporaries_of(a), 0);
    penumbra::OutputFiles output({a, b});
    output.write(a, "A");
    output.write(b, "B");
    output.commit();
    EXPECT_EQ(read_all(a), "A");
    EXPECT_EQ(read_all(b), "B");
}

// Through penumbra render: a symbolic link is written through, a FIFO is refused (and not
// opened), an existing file keeps its mode, a missing folder is reported before rendering.
TEST_F(Outputs, RenderWritesSafely) {
    const std::string small = "render builtin:default --width 32 --height 18 ";
    std::ofstream(dir_ / "real.png") << "old";
    fs::create_symlink("real.png", dir_ / "link.png");
    ASSERT_EQ(run(small + "-o link.png").exit_code, 0);
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "link.png")));
    EXPECT_EQ(penumbra::read_png(dir_ / "real.png").width, 32u);

    ASSERT_EQ(::mkfifo((dir_ / "fifo.png").c_str(), 0600), 0);
    const penumbra::testing::RunResult fifo = run(small + "-o fifo.png");
    EXPECT_EQ(fifo.exit_code, 2);
    EXPECT_NE(fifo.err.find("fifo.png: exists and is not a regular file"), std::string::npos) << fifo.err;
    EXPECT_TRUE(fs::is_fifo(dir_ / "fifo.png"));

    std::ofstream(dir_ / "private.png") << "old";
    fs::permissions(dir_ / "private.png", fs::perms::owner_read | fs::perms::owner_write);
    ASSERT_EQ(run(small + "-o private.png").exit_code, 0);
    EXPECT_EQ(fs::status(dir_ / "private.png").permissions() & fs::perms::all,
              fs::perms::owner_read | fs::perms::owner_write);

    const penumbra::testing::RunResult missing = run(small + "-o nodir/x.png");
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("nodir/x.png: the folder nodir does not exist"), std::string::npos) << missing.err;
}

// compare checks every output before it renders and traces, and writes all or nothing.
TEST_F(Outputs, CompareChecksEveryOutputFirst) {
    const penumbra::testing::RunResult result =
        run("compare builtin:default --width 32 --height 18 --out-dir cmp --json nodir/x.json");
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("nodir/x.json: the folder nodir does not exist"), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(dir_ / "cmp"));
}

}  // namespace
