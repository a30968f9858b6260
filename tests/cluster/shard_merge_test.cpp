// Sharded verification: the N slices of a list cover it exactly once and in order;
// `decode verify --shard K/N` runs merged by `decode merge-junit` give the testcases,
// counts and summary of one `--jobs 1` run; a missing or cut-short shard becomes an
// error for exactly its captures and the merge exits 2.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <filesystem>

#include "core/options.h"
#include "support/paths.h"
#include "verify/junit_merge.h"
#include "verify/shard.h"

namespace busdecode {
namespace {

TEST(Shard, SlicesPartitionTheListInOrder) {
    for (std::size_t total = 0; total <= 40; ++total)
        for (std::size_t n = 1; n <= 12; ++n) {
            std::size_t next = 0, smallest = total, largest = 0;
            for (std::size_t k = 1; k <= n; ++k) {
                const auto [first, last] = shardRange(total, {k, n});
                ASSERT_EQ(first, next) << total << " in " << k << "/" << n;
                smallest = std::min(smallest, last - first);
                largest = std::max(largest, last - first);
                next = last;
            }
            EXPECT_EQ(next, total);
            EXPECT_LE(largest - smallest, 1u);
        }
}

TEST(Shard, ParsesOneBasedKOfN) {
    EXPECT_EQ(parseShard("1/1").text(), "1/1");
    EXPECT_EQ(parseShard("7/7").index, 7u);
    for (const char* bad : {"0/3", "4/3", "3", "a/b", "1/0", "-1/2", "1/2/3", ""})
        EXPECT_THROW(parseShard(bad), InputError) << bad;
}

TEST(Shard, ListSkipsBlankAndCommentLines) {
    const std::string list = test::tempDir() + "/list.txt";
    test::writeFile(list, "a.vcd\r\n\n# note\nb c.vcd\n");
    EXPECT_EQ(readCaptureList(list), (std::vector<std::string>{"a.vcd", "b c.vcd"}));
    EXPECT_THROW(readCaptureList(list + ".absent"), InputError);
    EXPECT_THROW(readCaptureList(test::tempDir()), InputError);
}

struct ShardedBatch {
    std::string dir = test::tempDir() + "/sharded";
    std::string list = dir + "/list.txt";
    std::string rules = test::sourceDir() + "/captures/rules_bissc.toml";
    std::vector<std::string> captures;

    // 23 captures: passing, failing every fifth, one absent.
    ShardedBatch() {
        std::filesystem::create_directories(dir);
        std::string text;
        for (int i = 0; i < 23; ++i) {
            const std::string from = i % 5 == 4 ? "bissc_errors.vcd" : "bissc_1mhz_26bit.vcd";
            const std::string path = fmt::format("{}/cap-{:02}.vcd", dir, i);
            if (i != 11)
                std::filesystem::copy_file(test::sourceDir() + "/captures/" + from, path,
                                           std::filesystem::copy_options::overwrite_existing);
            captures.push_back(path);
            text += path + "\n";
        }
        test::writeFile(list, text);
    }
    test::RunResult verify(const std::vector<std::string>& extra) const {
        std::vector<std::string> args{"verify", "--from-list", list,           "--rules",
                                      rules,    "--opt",       "bissc.bits=26"};
        args.insert(args.end(), extra.begin(), extra.end());
        return test::runDecode(args);
    }
    std::string shardFile(int k) const { return fmt::format("{}/shard-{}.xml", dir, k); }
    test::RunResult merge(const std::vector<int>& shards, bool with_list) const {
        std::vector<std::string> args{"merge-junit", "-o", dir + "/all.xml"};
        for (int k : shards)
            args.push_back(shardFile(k));
        if (with_list) args.insert(args.end(), {"--from-list", list});
        return test::runDecode(args);
    }
};

void expectSameCases(const JunitShardFile& a, const JunitShardFile& b) {
    ASSERT_EQ(a.cases.size(), b.cases.size());
    for (std::size_t i = 0; i < a.cases.size(); ++i) {
        const auto &x = a.cases[i], &y = b.cases[i];
        EXPECT_EQ(std::tie(x.name, x.classname, x.outcome, x.message, x.type, x.text),
                  std::tie(y.name, y.classname, y.outcome, y.message, y.type, y.text))
            << i;
    }
    EXPECT_EQ(a.out, b.out);
    EXPECT_EQ(a.err, b.err);
}

std::string lastLine(const std::string& s) {
    const auto end = s.find_last_not_of('\n');
    return s.substr(s.rfind('\n', end) + 1, end - s.rfind('\n', end));
}

TEST(MergeJunit, ShardsMergeToTheSingleRun) {
    ShardedBatch run;
    const auto single = run.verify({"--jobs", "1", "--junit", run.dir + "/single.xml"});
    ASSERT_EQ(single.status, 2) << single.err;  // the absent capture
    for (int k = 1; k <= 4; ++k)
        run.verify({"--shard", fmt::format("{}/4", k), "--junit", run.shardFile(k)});
    const auto merged = run.merge({3, 1, 4, 2}, true);  // any order: the shard property sorts
    EXPECT_EQ(merged.status, 2) << merged.err;
    EXPECT_EQ(merged.out, lastLine(single.out) + "\n");
    EXPECT_EQ(merged.err, "");
    expectSameCases(readJunitShard(run.dir + "/single.xml"), readJunitShard(run.dir + "/all.xml"));
    EXPECT_EQ(test::runCommand("xmllint --noout --schema " + test::sourceDir() +
                               "/tests/report/junit_ant.xsd " + run.dir + "/all.xml")
                  .status,
              0);
}

TEST(MergeJunit, AMissingShardIsAnErrorForExactlyItsCaptures) {
    ShardedBatch run;
    for (int k = 1; k <= 3; ++k)
        run.verify({"--shard", fmt::format("{}/3", k), "--junit", run.shardFile(k)});
    test::writeFile(run.shardFile(3),
                    test::readFile(run.shardFile(3)).substr(0, 300));  // cut short
    for (bool with_list : {true, false}) {
        const auto merged = run.merge({1, 2, 3}, with_list);
        EXPECT_EQ(merged.status, 2);
        EXPECT_NE(merged.err.find("shard 3/3: no usable JUnit file"), std::string::npos)
            << merged.err;
        std::vector<std::string> errors;
        for (const auto& c : readJunitShard(run.dir + "/all.xml").cases)
            if (c.outcome == "error" && c.type == "shard") errors.push_back(c.classname);
        // With the list, the shard's captures under the class names a single run gives them.
        const auto names = junitClassNames(run.captures);
        const auto [first, last] = shardRange(names.size(), {3, 3});
        const auto expected = with_list
                                  ? std::vector<std::string>(names.begin() + std::ptrdiff_t(first),
                                                             names.begin() + std::ptrdiff_t(last))
                                  : std::vector<std::string>{"shard 3/3"};
        EXPECT_EQ(errors, expected);
    }
}

TEST(MergeJunit, EveryShardMissingLeavesEveryCaptureAnError) {
    ShardedBatch run;
    const auto merged = run.merge({}, true);
    EXPECT_EQ(merged.status, 2);
    EXPECT_EQ(merged.out,
              "23 captures: 0 passed, 0 failed, 23 unreadable; 0 rule checks, 0 failed\n");
    EXPECT_EQ(merged.err,
              "decode merge-junit: 23 of the list's 23 captures have no verdict in any JUnit file "
              "given\n");
}

TEST(MergeJunit, OnlyUnusableFilesMergeToAnErrorNeverAPass) {
    ShardedBatch run;
    test::writeFile(run.shardFile(1), "not xml");
    const auto merged = run.merge({1}, false);
    EXPECT_EQ(merged.status, 2);
    const auto cases = readJunitShard(run.dir + "/all.xml").cases;
    ASSERT_EQ(cases.size(), 1u);
    EXPECT_EQ(cases[0].outcome, "error");
    EXPECT_EQ(cases[0].classname, run.shardFile(1));
    EXPECT_NE(cases[0].message.find("not well-formed JUnit XML"), std::string::npos)
        << cases[0].message;
}

TEST(MergeJunit, ShardsOfAnotherListOrOtherRulesAreNotMergedSilently) {
    ShardedBatch run;
    for (int k = 1; k <= 2; ++k)
        run.verify({"--shard", fmt::format("{}/2", k), "--junit", run.shardFile(k)});
    const std::string reversed = run.dir + "/reversed.txt";
    std::string text;
    for (auto it = run.captures.rbegin(); it != run.captures.rend(); ++it)
        text += *it + "\n";
    test::writeFile(reversed, text);
    auto r = test::runDecode({"merge-junit", run.shardFile(1), run.shardFile(2), "-o",
                              run.dir + "/all.xml", "--from-list", reversed});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find(run.shardFile(1) + ": "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("not in shard 1/2 of the --from-list"), std::string::npos) << r.err;
    // Shard 2 checked against other rules.
    const std::string other = run.dir + "/other_rules.toml";
    test::writeFile(other, test::readFile(run.rules));
    test::runDecode({"verify", "--from-list", run.list, "--rules", other, "--opt", "bissc.bits=26",
                     "--shard", "2/2", "--junit", run.shardFile(2)});
    std::filesystem::remove(run.dir + "/all.xml");
    r = run.merge({1, 2}, true);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("checked against the rules " + other), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(run.dir + "/all.xml"));
}

// The rules file's name alone is no proof: a shard run with the same name but other
// contents, or other decoding options, is refused too.
TEST(MergeJunit, ShardsCheckedWithOtherContentsOrOptionsAreNotMerged) {
    ShardedBatch run;
    const std::string text = test::readFile(run.rules);
    run.rules = run.dir + "/rules.toml";  // a copy of its own, edited below
    test::writeFile(run.rules, text);
    const std::string refused = "checked with other rules or decode options than ";
    run.verify({"--shard", "1/2", "--junit", run.shardFile(1)});
    run.verify({"--shard", "2/2", "--junit", run.shardFile(2), "--opt", "bissc.crc_bits=6"});
    auto r = run.merge({1, 2}, true);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find(run.shardFile(2) + ": " + refused + run.shardFile(1)), std::string::npos)
        << r.err;
    test::writeFile(run.rules, text + "\n# edited between the shards\n");
    run.verify({"--shard", "2/2", "--junit", run.shardFile(2)});
    r = run.merge({1, 2}, true);
    EXPECT_NE(r.err.find(refused), std::string::npos) << r.err;
    test::writeFile(run.rules, text);
    run.verify({"--shard", "2/2", "--junit", run.shardFile(2)});
    r = run.merge({1, 2}, true);
    EXPECT_EQ(r.err.find(refused), std::string::npos) << r.err;  // the same checks merge
    EXPECT_NE(r.out.find("23 captures: "), std::string::npos) << r.out;
}

TEST(MergeJunit, BadInputIsOneLineAndExit2WithNoFile) {
    ShardedBatch run;
    run.verify({"--shard", "1/2", "--junit", run.shardFile(1)});
    run.verify({"--shard", "1/3", "--junit", run.shardFile(2)});
    std::filesystem::remove(run.dir + "/all.xml");
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"merge-junit", run.shardFile(1)},
             {"merge-junit", run.shardFile(1), run.shardFile(2), "-o", run.dir + "/all.xml"},
             {"merge-junit", run.shardFile(1), "-o", run.shardFile(1)},
             {"merge-junit", run.shardFile(1), "--bogus", "-o", run.dir + "/all.xml"},
             {"merge-junit", run.shardFile(1), "-o", "-"},
             {"merge-junit", run.shardFile(1), "-o", run.dir + "/all.xml", "-o",
              run.dir + "/other.xml"},
             {"merge-junit", run.shardFile(1), "-o", run.dir + "/all.xml", "--from-list", run.list,
              "--from-list", run.list}}) {
        const auto r = test::runDecode(args);
        EXPECT_EQ(r.status, 2) << args.back();
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(std::filesystem::exists(run.dir + "/all.xml"));
    }
    for (const char* shard : {"0/2", "3/2", "x"}) {
        const auto r = run.verify({"--shard", shard});
        EXPECT_EQ(r.status, 2);
        EXPECT_NE(r.err.find("--shard"), std::string::npos) << r.err;
    }
}

TEST(VerifyShard, AnEmptySliceWritesAnEmptyPassingFile) {
    ShardedBatch run;
    const std::string list = run.dir + "/two.txt";
    test::writeFile(list, run.captures[0] + "\n" + run.captures[1] + "\n");
    const auto r =
        test::runDecode({"verify", "--from-list", list, "--rules", run.rules, "--opt",
                         "bissc.bits=26", "--shard", "1/3", "--junit", run.shardFile(9)});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, "0 captures: 0 passed, 0 failed, 0 unreadable; 0 rule checks, 0 failed\n");
    EXPECT_TRUE(readJunitShard(run.shardFile(9)).cases.empty());
}

}  // namespace
}  // namespace busdecode
