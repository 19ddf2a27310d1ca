// Output files (apps/image/output_files.hpp): all or nothing, through symbolic links, never
// over a non-regular file, permissions kept, and nothing left behind, also when the process
// is interrupted by a signal (issue 17, items 8-10). In-process, and through `penumbra`.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

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

// SIGTERM while a set is half written: the temporaries go, the process still dies of SIGTERM.
TEST_F(Outputs, TemporariesAreRemovedWhenTheProcessIsTerminated) {
    const fs::path a = dir_ / "a.png";
    const fs::path b = dir_ / "b.json";
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        penumbra::OutputFiles output({a, b});
        output.write(a, "first file");
        std::raise(SIGTERM);
        _exit(0);  // not reached
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
    EXPECT_FALSE(fs::exists(penumbra::temporary_output_path(a)));
    EXPECT_FALSE(fs::exists(a));
    EXPECT_FALSE(fs::exists(b));
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
    EXPECT_FALSE(fs::exists(penumbra::temporary_output_path(a)));
    penumbra::OutputFiles output({a, b});
    output.write(a, "A");
    output.write(b, "B");
    output.commit();
    EXPECT_EQ(read_all(a), "A");
    EXPECT_EQ(read_all(b), "B");
}

// Through penumbra render: a symbolic link is written through, a FIFO is refused (and not
// opened), an existing file keeps its mode, a leftover temporary of a killed run is
// replaced, a missing folder is reported before rendering.
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

    std::ofstream(penumbra::temporary_output_path(dir_ / "left.png")) << "a killed run's leftover";
    ASSERT_EQ(run(small + "-o left.png").exit_code, 0);
    EXPECT_FALSE(fs::exists(penumbra::temporary_output_path(dir_ / "left.png")));

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
