// Outputs through the real CLI: --report and --junit replace only a regular file (or
// create a new one); a character device, a FIFO or a symlink is written through and
// stays what it was. Reports of several captures get a file each, whatever their names. An
// LCM log that a full disk cut short is an error and removed.
// The devices are this test's own nodes (mknod, as root), never /dev/null itself.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <filesystem>
#include <tuple>
#include <vector>

#include "spi_vcd.h"
#include "support/paths.h"

using namespace busdecode::test;
namespace fs = std::filesystem;

namespace {

std::string decode() {
    return shellQuote(binDir() + "/decode");
}

std::string smallCapture() {
    return spiCapture("words.vcd", 20, 10'000);
}

mode_t typeOf(const std::string& path) {
    struct stat st {};
    if (lstat(path.c_str(), &st) != 0) return 0;
    return st.st_mode & S_IFMT;
}

// A character device node like /dev/null (1,3) or /dev/full (1,7) in the test's own
// directory; empty when this is not root (or the container forbids mknod).
std::string deviceNode(const std::string& name, unsigned minor) {
    const std::string path = tempDir() + "/" + name;
    if (mknod(path.c_str(), S_IFCHR | 0666, makedev(1, minor)) != 0) return "";
    return path;
}

TEST(OutputSafety, ReportOnNullDeviceKeepsTheDevice) {
    const std::string null = deviceNode("null", 3);
    if (null.empty()) GTEST_SKIP() << "mknod needs root";
    const RunResult r = runCommand(decode() + " " + shellQuote(smallCapture()) +
                                   " --proto spi --report " + shellQuote(null) + " >/dev/null");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(typeOf(null), S_IFCHR);
    EXPECT_EQ(typeOf("/dev/null"), S_IFCHR);
}

TEST(OutputSafety, ReportOnFullDeviceIsAWriteError) {
    const std::string full = deviceNode("full", 7);
    if (full.empty()) GTEST_SKIP() << "mknod needs root";
    const RunResult r = runCommand(decode() + " " + shellQuote(smallCapture()) +
                                   " --proto spi --report " + shellQuote(full) + " >/dev/null");
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "decode: " + full + ": cannot write: No space left on device\n");
    EXPECT_EQ(typeOf(full), S_IFCHR);
}

// LCM's file provider drops its write errors; the log is read back. A file size limit
// (ulimit -f, SIGXFSZ ignored) fails the writes past 64 KiB as a full disk would.
TEST(OutputSafety, AnLcmLogCutShortByAFullDiskIsAnErrorAndRemoved) {
    const std::string capture = spiCapture("lcm_log.vcd", 2000, 10'000);
    const std::string log = tempDir() + "/full.lcm";
    const RunResult r =
        runCommand("trap '' XFSZ; ulimit -f 64; " + decode() + " " + shellQuote(capture) +
                   " --proto spi --lcm " + shellQuote("file://" + log + "?mode=w") + " >/dev/null");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err.rfind("decode: --lcm: " + log + ": the log holds ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("writing it failed (disk full?); removed\n"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(log));
    // Without the limit the same run writes the whole log.
    const RunResult whole =
        runCommand(decode() + " " + shellQuote(capture) + " --proto spi --lcm " +
                   shellQuote("file://" + log + "?mode=w") + " >/dev/null");
    EXPECT_EQ(whole.status, 0) << whole.err;
    EXPECT_GT(fs::file_size(log), 64u << 10);
}

// Runs `decode ARGS` with a reader on the FIFO `f` and returns what the reader got.
std::string throughFifo(const std::string& f, const std::string& args, RunResult& r) {
    EXPECT_EQ(mkfifo(f.c_str(), 0600), 0);
    const std::string got = f + ".got";
    r = runCommand("timeout -s KILL 20 cat " + shellQuote(f) + " >" + shellQuote(got) +
                   " & reader=$!; " + decode() + " " + args +
                   " >/dev/null; s=$?; wait $reader; exit $s");
    EXPECT_EQ(typeOf(f), S_IFIFO);
    return fs::exists(got) ? readFile(got) : "";
}

TEST(OutputSafety, ReportOnFifoIsWrittenThrough) {
    const std::string f = tempDir() + "/report.fifo";
    RunResult r;
    const std::string got =
        throughFifo(f, shellQuote(smallCapture()) + " --proto spi --report " + shellQuote(f), r);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(got.rfind("busdecode report\n", 0), 0u) << got;
}

TEST(OutputSafety, JunitOnFifoIsWrittenThrough) {
    const std::string f = tempDir() + "/junit.fifo";
    RunResult r;
    const std::string got = throughFifo(f,
                                        "verify " + shellQuote(smallCapture()) + " --rules " +
                                            shellQuote(spiRules()) + " --junit " + shellQuote(f),
                                        r);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(got.find("<testsuite"), std::string::npos) << got;
}

TEST(OutputSafety, ReportOnSymlinkWritesItsTarget) {
    const std::string dir = tempDir() + "/linked";
    fs::create_directories(dir);
    writeFile(dir + "/target.txt", "old\n");
    fs::create_symlink("target.txt", dir + "/link.txt");
    const RunResult r =
        runCommand(decode() + " " + shellQuote(smallCapture()) + " --proto spi --report " +
                   shellQuote(dir + "/link.txt") + " >/dev/null");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(typeOf(dir + "/link.txt"), S_IFLNK);
    EXPECT_EQ(fs::read_symlink(dir + "/link.txt"), "target.txt");
    EXPECT_EQ(readFile(dir + "/target.txt").rfind("busdecode report\n", 0), 0u);
}

TEST(OutputSafety, ReportOnSymlinkToStdoutGoesToStdout) {
    // Like /dev/stdout, in the test's own directory.
    const std::string link = tempDir() + "/stdout.txt";
    fs::create_symlink("/proc/self/fd/1", link);
    const RunResult r = runCommand(decode() + " " + shellQuote(smallCapture()) +
                                   " --proto spi --report " + shellQuote(link));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(typeOf(link), S_IFLNK);
    EXPECT_NE(r.out.find("busdecode report\n"), std::string::npos) << r.out;
}

TEST(OutputSafety, ReportsOfCapturesWithOneNameAreDistinct) {
    const std::string dir = tempDir() + "/same_names";
    for (const std::string sub : {"d1", "d2"}) {
        fs::create_directories(dir + "/" + sub);
        writeFile(dir + "/" + sub + "/x.vcd", spiVcd(sub == "d1" ? 3 : 5, 10'000));
    }
    const RunResult r =
        runCommand("cd " + shellQuote(dir) + " && " + decode() +
                   " d1/x.vcd d2/x.vcd d1/x.vcd --proto spi --report r.txt >/dev/null");
    EXPECT_EQ(r.status, 0) << r.err;
    const std::string first = readFile(dir + "/r-x.vcd.txt");
    const std::string second = readFile(dir + "/r-x.vcd-2.txt");
    const std::string third = readFile(dir + "/r-x.vcd-3.txt");
    EXPECT_NE(first.find("d1/x.vcd"), std::string::npos) << first;
    EXPECT_NE(second.find("d2/x.vcd"), std::string::npos) << second;
    EXPECT_NE(third.find("d1/x.vcd"), std::string::npos) << third;
}

TEST(OutputSafety, ReplacedReportKeepsItsMode) {
    const std::string report = tempDir() + "/private.txt";
    writeFile(report, "old\n");
    ASSERT_EQ(chmod(report.c_str(), 0600), 0);
    const RunResult r = runCommand(decode() + " " + shellQuote(smallCapture()) +
                                   " --proto spi --report " + shellQuote(report) + " >/dev/null");
    EXPECT_EQ(r.status, 0) << r.err;
    struct stat st {};
    ASSERT_EQ(stat(report.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0600u);
    EXPECT_EQ(readFile(report).rfind("busdecode report\n", 0), 0u);
}

TEST(OutputSafety, ReportOnTheCaptureIsRefused) {
    const std::string capture = spiCapture("self.vcd", 3, 10'000);
    const std::string before = readFile(capture);
    const std::string link = tempDir() + "/self_link.vcd";
    fs::create_symlink(capture, link);
    for (const auto& report : {capture, link}) {
        const RunResult r = runCommand(decode() + " " + shellQuote(capture) +
                                       " --proto spi --report " + shellQuote(report));
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(r.err, "decode: --report " + report + ": is the capture " + capture +
                             ", not an output\n");
        EXPECT_EQ(readFile(capture), before);
    }
    const RunResult v = runCommand(decode() + " verify " + shellQuote(capture) + " --rules " +
                                   shellQuote(spiRules()) + " --junit " + shellQuote(capture));
    EXPECT_EQ(v.status, 2);
    EXPECT_EQ(v.err, "decode verify: --junit " + capture + ": is the capture " + capture +
                         ", not an output\n");
    EXPECT_EQ(readFile(capture), before);
}

TEST(OutputSafety, JunitOnTheRulesOrTheListIsRefused) {
    const std::string capture = spiCapture("listed.vcd", 3, 10'000);
    const std::string rules = tempDir() + "/own_rules.toml";
    writeFile(rules, readFile(spiRules()));
    const std::string list = tempDir() + "/captures.txt";
    writeFile(list, capture + "\n");
    for (const auto& [args, junit, what] :
         {std::tuple<std::string, std::string, std::string>{shellQuote(capture), rules,
                                                            "rules file"},
          {"--from-list " + shellQuote(list), list, "capture list"}}) {
        const std::string before = readFile(junit);
        const RunResult r = runCommand(decode() + " verify " + args + " --rules " +
                                       shellQuote(rules) + " --junit " + shellQuote(junit));
        EXPECT_EQ(r.status, 2);
        EXPECT_EQ(r.err, "decode verify: --junit " + junit + ": is the " + what + " " + junit +
                             ", not an output\n");
        EXPECT_EQ(readFile(junit), before);
    }
}

TEST(OutputSafety, LcmLogOnTheCaptureIsRefused) {
    const std::string capture = spiCapture("logged.vcd", 3, 10'000);
    const std::string before = readFile(capture);
    const RunResult r = runCommand(decode() + " " + shellQuote(capture) + " --proto spi --lcm " +
                                   shellQuote("file://" + capture + "?mode=w"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err,
              "decode: --lcm " + capture + ": is the capture " + capture + ", not an output\n");
    EXPECT_EQ(readFile(capture), before);
}

TEST(OutputSafety, TwoOutputsOnOneFileAreRefused) {
    const std::string log = tempDir() + "/both.out";
    const RunResult r =
        runCommand(decode() + " " + shellQuote(smallCapture()) + " --proto spi --report " +
                   shellQuote(log) + " --lcm " + shellQuote("file://" + log + "?mode=w"));
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err, "decode: --lcm " + log + ": --report writes there too\n");
    EXPECT_FALSE(fs::exists(log));
}

TEST(OutputSafety, ReportsOfSeveralCapturesOnADeviceAreWrittenThrough) {
    const std::string dir = tempDir() + "/device_reports";
    fs::create_directories(dir);
    const std::string null = deviceNode("device_reports/null", 3);
    if (null.empty()) GTEST_SKIP() << "mknod needs root";
    const RunResult r = runCommand(decode() + " " + shellQuote(smallCapture()) + " " +
                                   shellQuote(spiCapture("second.vcd", 3, 10'000)) +
                                   " --proto spi --report " + shellQuote(null) + " >/dev/null");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(typeOf(null), S_IFCHR);
    std::vector<std::string> made;  // no "null-words.vcd" beside the device
    for (const auto& entry : fs::directory_iterator(dir))
        made.push_back(entry.path().filename().string());
    EXPECT_EQ(made, std::vector<std::string>{"null"});
}

TEST(OutputSafety, PathsThatAreNotUtf8AreUsedAsGiven) {
    // A Latin-1 name ("café.vcd", "ré.txt") must not turn into U+FFFD on the way.
    const std::string capture = tempDir() + "/caf\xE9.vcd";
    writeFile(capture, readFile(smallCapture()));
    const std::string report = tempDir() + "/r\xE9.txt";
    const RunResult r = runCommand(decode() + " " + shellQuote(capture) + " --proto spi --report " +
                                   shellQuote(report) + " >/dev/null");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(readFile(report).rfind("busdecode report\n", 0), 0u);
}

}  // namespace
