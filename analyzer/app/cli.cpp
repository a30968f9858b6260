// The `decode` command line: argument parsing (Qt's QCommandLineParser), plugin
// loading, and wiring captures, decoders and sinks together. Every user error is one
// line on stderr and exit status 2.
#include "cli.h"

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <map>
#include <system_error>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <QCommandLineParser>
#include <QCoreApplication>

#include "app/decode_args.h"
#include "app/interruption.h"
#include "app/list_decoders.h"
#include "app/output_guard.h"
#include "app/plugin_loader.h"
#include "app/report_paths.h"
#include "app/standard_streams.h"
#include "capture/analog_lines.h"
#include "capture/format_list.h"
#include "core/atomic_file.h"
#include "core/interrupted.h"
#include "core/options.h"
#include "core/registry.h"
#include "core/sample_rate.h"
#include "lcm/lcm_sink.h"
#include "lcm/monitor.h"
#include "report/report_sink.h"
#include "sinks/stream_sinks.h"
#include "verify/junit_merge.h"
#include "verify/verify.h"
#if BUSDECODE_LIVE
#include "live_module.h"
#endif

namespace busdecode {

namespace {

// QString is UTF-16: argument bytes that are not UTF-8 (a Latin-1 file name) come back
// from it as U+FFFD and name no file. So each value maps back to the bytes it came from.
std::map<QString, std::string>& rawArguments() {
    static std::map<QString, std::string> raw;
    return raw;
}

void rememberRawArguments(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string raw = argv[i];
        rawArguments().emplace(QString::fromLocal8Bit(raw), raw);
        if (const auto eq = raw.find('='); raw.rfind("--", 0) == 0 && eq != std::string::npos)
            rawArguments().emplace(QString::fromLocal8Bit(raw.substr(eq + 1)), raw.substr(eq + 1));
    }
}

std::string bytesOf(const QString& s) {
    const auto it = rawArguments().find(s);
    return it == rawArguments().end() ? s.toStdString() : it->second;
}

std::vector<std::string> toStd(const QStringList& l) {
    std::vector<std::string> out;
    for (const auto& s : l)
        out.push_back(bytesOf(s));
    return out;
}

// `--lcm` takes an optional URL: `--lcm udpm://...`, `--lcm=URL`, or bare `--lcm`.
// QCommandLineParser has no optional values, so rewrite to `--lcm=...` first.
QStringList normaliseArgs(int argc, char** argv) {
    QStringList out;
    for (int i = 0; i < argc; ++i) {
        QString a = QString::fromLocal8Bit(argv[i]);
        if (a == "--lcm") {
            if (i + 1 < argc && QString::fromLocal8Bit(argv[i + 1]).contains("://")) {
                out << "--lcm=" + QString::fromLocal8Bit(argv[++i]);
            } else {
                out << "--lcm=default";
            }
            continue;
        }
        out << a;
    }
    return out;
}

struct Parsed {
    DecodeArgs args;
    bool list = false;
    bool done = false;     // --help or --version printed
    bool formats = false;  // --formats: the capture formats, or what each capture is
    bool scan = false;     // --scan: the attached analysers
};

// Every option with its help text, in the order --help lists them.
void addOptions(QCommandLineParser& p) {
    p.setApplicationDescription(
        "Decode logic-analyser captures of encoder and motion-control buses.");
    p.addPositionalArgument("CAPTURE", "VCD, CSV or sigrok .sr capture; - reads standard input",
                            "CAPTURE...");
    QCommandLineOption proto("proto", "decoder to run (repeat for several buses)", "NAME");
    QCommandLineOption map("map", "bind a decoder role to a capture signal", "ROLE=SIGNAL");
    QCommandLineOption opt("opt", "set a decoder option", "KEY=VALUE");
    QCommandLineOption format("format", "output format: text or jsonl", "FORMAT", "text");
    QCommandLineOption report("report", "write a text or .html report", "FILE");
    QCommandLineOption lcm("lcm", "publish events over LCM (optional URL)", "URL");
    QCommandLineOption rate("rate", "sample rate for CSV files without time or rate", "HZ");
    QCommandLineOption threshold("threshold",
                                 "analog lines: switching threshold for all lines, or one line's",
                                 "[SIGNAL=]V");
    QCommandLineOption hysteresis("hysteresis", "analog lines: hysteresis band width", "V");
    QCommandLineOption follow("follow", "keep reading a growing capture (or a pipe)");
    QCommandLineOption realtime("realtime", "pace a recorded capture at its own time scale");
    QCommandLineOption list("list", "list decoders, roles, options and defaults");
    QCommandLineOption formats("formats", "list capture formats; with CAPTURE..., describe each");
    QCommandLineOption rules("rules", "verify: rules file (TOML)", "FILE");
    QCommandLineOption junit("junit", "verify: write JUnit XML", "FILE");
    QCommandLineOption jobs("jobs", "verify: captures checked in parallel (0 = one per core)", "N",
                            "0");
    QCommandLineOption shard("shard", "verify: check only the K-th of N slices (K from 1)", "K/N");
    QCommandLineOption from_list("from-list", "verify: read captures from FILE, one a line",
                                 "FILE");
    QCommandLineOption threads(
        "threads", "per capture: 1 reads and decodes on one thread, 2 reads ahead on another", "N",
        "2");
    QCommandLineOption device("device", "acquire live through libsigrok (or playback:file=X.sr)",
                              "DRIVER[:conn=...]");
    QCommandLineOption samplerate("samplerate", "live: the analyser's sample rate", "HZ");
    QCommandLineOption channels("channels", "live: the logic channels to acquire", "D0,D1,...");
    QCommandLineOption samples("samples", "live: stop after N samples", "N");
    QCommandLineOption seconds("time", "live: stop after this many seconds of samples", "SECONDS");
    QCommandLineOption save("save", "live: also write the samples as a sigrok session", "FILE.sr");
    QCommandLineOption scan("scan", "list the analysers libsigrok finds");
    QCommandLineOption help({"h", "help"}, "show this help");
    QCommandLineOption version("version", "show the version");
    for (auto* o : {&proto,     &map,        &opt,      &format,    &report,  &lcm,     &rate,
                    &threshold, &hysteresis, &follow,   &realtime,  &list,    &formats, &rules,
                    &junit,     &jobs,       &shard,    &from_list, &threads, &help,    &version,
                    &device,    &samplerate, &channels, &samples,   &seconds, &save,    &scan})
        p.addOption(*o);
}

// --help and --version print and end the run.
bool printedHelpOrVersion(const QCommandLineParser& p) {
    if (p.isSet("h")) {
        fmt::print("{}", p.helpText().toStdString());
        fmt::print(
            "\nCommands:\n  decode CAPTURE... --proto NAME [...]\n"
            "  decode verify CAPTURE... --rules FILE [--junit FILE] [--jobs N] [--threads N]\n"
            "                [--from-list FILE] [--shard K/N]\n"
            "  decode --device DRIVER[:conn=...] --samplerate HZ [--channels D0,...]\n"
            "         [--samples N | --time SECONDS] [--save FILE.sr] --proto NAME [...]\n"
            "  decode --scan\n"
            "  decode merge-junit SHARD.xml... -o ALL.xml [--from-list FILE]\n"
            "  decode monitor [--lcm URL]\n  decode --list\n");
        return true;
    }
    if (p.isSet("version")) {
        fmt::print("decode (busdecode) 0.1.0\n");
        return true;
    }
    return false;
}

void readLiveArgs(const QCommandLineParser& p, DecodeArgs& a) {
    a.device = bytesOf(p.value("device"));
    a.samplerate = bytesOf(p.value("samplerate"));
    a.channels = bytesOf(p.value("channels"));
    a.samples = bytesOf(p.value("samples"));
    a.seconds = bytesOf(p.value("time"));
    a.save = bytesOf(p.value("save"));
    if (a.device.empty() && (p.isSet("samplerate") || p.isSet("channels") || p.isSet("samples") ||
                             p.isSet("time") || p.isSet("save")))
        throw InputError("--samplerate, --channels, --samples, --time and --save need --device");
}

void readDecodeArgs(const QCommandLineParser& p, DecodeArgs& a) {
    a.captures = toStd(p.positionalArguments());
    a.protos = toStd(p.values("proto"));
    a.maps = toStd(p.values("map"));
    a.opts = toStd(p.values("opt"));
    a.format = bytesOf(p.value("format"));
    if (a.format != "text" && a.format != "jsonl")
        throw InputError(fmt::format("--format {}: expected text or jsonl", a.format));
    a.report = bytesOf(p.value("report"));
    if (p.isSet("lcm"))
        a.lcm_url = p.value("lcm") == "default" ? std::string() : bytesOf(p.value("lcm"));
    if (p.isSet("rate")) {
        a.rate_hz = rateArgument("--rate", bytesOf(p.value("rate")));
    }
    for (const auto& t : toStd(p.values("threshold")))
        a.thresholds.push_back(parseThresholdOption(t));
    if (p.isSet("hysteresis")) a.hysteresis = parseHysteresisOption(bytesOf(p.value("hysteresis")));
    a.follow = p.isSet("follow");
    a.realtime = p.isSet("realtime");
}

void readVerifyAndThreadArgs(const QCommandLineParser& p, DecodeArgs& a) {
    a.rules = bytesOf(p.value("rules"));
    a.junit = bytesOf(p.value("junit"));
    a.shard = bytesOf(p.value("shard"));
    a.from_list = bytesOf(p.value("from-list"));
    auto j = parseInteger(bytesOf(p.value("jobs")));
    if (!j || *j < 0 || *j > 256)
        throw InputError("--jobs: expected a whole number from 0 (all cores) to 256");
    a.jobs = int(*j);
    const std::string t = bytesOf(p.value("threads"));
    if (t != "1" && t != "2")
        throw InputError(fmt::format(
            "--threads {}: expected 1 (read and decode on one thread) or 2 (read ahead on a "
            "second)",
            t));
    a.threads = t == "1" ? 1 : 2;
}

// An option of one value given twice (the last would win without a word), a file option
// or a capture given as "" (read or written nowhere), or plain decode's outputs given to
// verify (which prints verdicts and writes JUnit only).
// Qt names an unknown option without its dashes ("Unknown option 'bogus'."): the
// argument as it was typed says which one.
std::string parseErrorText(const QCommandLineParser& p, const QStringList& argv) {
    const QStringList unknown = p.unknownOptionNames();
    if (unknown.isEmpty()) return p.errorText().toStdString();
    for (const QString& arg : argv) {
        const QString name = arg.section('=', 0, 0);
        if (name == "-" + unknown.front() || name == "--" + unknown.front())
            return fmt::format("unknown option '{}' (see decode --help)", name.toStdString());
    }
    return fmt::format("unknown option '{}' (see decode --help)", unknown.front().toStdString());
}

void checkOptionValues(const QCommandLineParser& p, bool verify) {
    for (const char* name :
         {"format", "report", "lcm", "rate", "hysteresis", "rules", "junit", "jobs", "shard",
          "from-list", "threads", "device", "samplerate", "channels", "samples", "time", "save"})
        if (p.isSet(name) && p.values(name).size() > 1)
            throw InputError(fmt::format("--{} is given {} times: it takes one value", name,
                                         p.values(name).size()));
    for (const char* name : {"report", "rules", "junit", "from-list", "save"})
        if (p.isSet(name) && p.value(name).isEmpty())
            throw InputError(fmt::format("--{}: the file name is empty", name));
    for (const char* name : {"report", "junit", "save"})
        if (p.isSet(name) && p.value(name) == "-")
            throw InputError(fmt::format(
                "--{} -: standard output carries the {}; name a file (/dev/stdout to share it)",
                name, verify ? "verdicts" : "events"));
    for (const auto& capture : p.positionalArguments())
        if (capture.isEmpty()) throw InputError("a capture's name is empty (\"\")");
    // The second would find standard input already read to its end.
    if (p.positionalArguments().count("-") > 1)
        throw InputError("standard input (-) is given as a capture twice: it can be read once");
    if (p.isSet("shard") && p.value("shard").isEmpty())  // an unset $SLURM_ARRAY_TASK_ID
        throw InputError("--shard: expected K/N (e.g. 2/8), got nothing");
    for (const char* name : {"device", "samplerate", "channels", "samples", "time"})
        if (p.isSet(name) && p.value(name).trimmed().isEmpty())  // an unset shell variable
            throw InputError(fmt::format("--{}: expected a value, got nothing", name));
    if (verify)
        for (const char* name : {"format", "report", "lcm", "follow", "realtime"})
            if (p.isSet(name))
                throw InputError(
                    fmt::format("--{} belongs to plain 'decode', not to 'decode verify' (which "
                                "prints a verdict a capture; --junit writes them)",
                                name));
}

// Options that belong to another command, or a run with nothing to read.
void checkCombinations(const Parsed& out, bool verify) {
    const DecodeArgs& a = out.args;
    if (!verify &&
        (!a.rules.empty() || !a.junit.empty() || !a.shard.empty() || !a.from_list.empty()))
        throw InputError("--rules, --junit, --shard and --from-list belong to 'decode verify'");
    if (verify && a.rules.empty()) throw InputError("decode verify: --rules FILE is required");
    if (!a.device.empty() && (!a.captures.empty() || verify || a.follow))
        throw InputError("--device acquires live: no capture file, --follow or verify with it");
    if (!out.list && !out.formats && !out.scan && a.device.empty() && a.captures.empty() &&
        a.from_list.empty())
        throw InputError("no capture given (see decode --help)");
}

Parsed parse(const QStringList& argv, bool verify) {
    QCommandLineParser p;
    addOptions(p);
    if (!p.parse(argv)) throw InputError(parseErrorText(p, argv));
    if (printedHelpOrVersion(p)) return {{}, false, true};
    checkOptionValues(p, verify);
    Parsed out;
    out.list = p.isSet("list");
    out.formats = p.isSet("formats");
    out.scan = p.isSet("scan");
    readLiveArgs(p, out.args);
    readDecodeArgs(p, out.args);
    readVerifyAndThreadArgs(p, out.args);
    checkCombinations(out, verify);
    return out;
}

int runFormats(const DecodeArgs& a) {
    if (a.captures.empty()) printFormatList(stdout);
    OpenOptions open;
    open.rate_hz = a.rate_hz;
    for (const auto& capture : a.captures)
        printCaptureDescription(stdout, capture, open);
    return 0;
}

// One capture's sinks: the output on stdout, its report, and the shared LCM sink.
struct OutputSinks {
    std::vector<std::unique_ptr<OutputSink>> owned;
    std::vector<OutputSink*> sinks;
    OutputSinks(const DecodeArgs& a, const std::string& report, bool several, OutputSink* lcm) {
        owned.push_back(a.format == "jsonl" ? makeJsonlSink(stdout, several)
                                            : makeTextSink(stdout));
        if (!report.empty()) owned.push_back(makeReportSink(report));
        for (auto& s : owned)
            sinks.push_back(s.get());
        if (lcm) sinks.push_back(lcm);
    }
};

// Refuses, before anything is opened, an output on an input or two outputs on one file:
// the reports, the --save session and the LCM log.
void guardOutputs(const DecodeArgs& a, const std::vector<NamedFile>& inputs,
                  const std::vector<std::string>& reports) {
    std::vector<NamedFile> outputs;
    for (const auto& report : reports)
        if (!report.empty()) outputs.push_back({"--report", report});
    if (!a.save.empty()) outputs.push_back({"--save", a.save});
    if (a.lcm_url && !lcmLogFile(*a.lcm_url).empty())
        outputs.push_back({"--lcm", lcmLogFile(*a.lcm_url)});
    for (const auto& out : outputs)
        refuseOutputOnInputs(out.what, out.path, inputs);
    refuseSharedOutputs(outputs);
}

// Live output wants every line at once; a batch run wants big writes.
void bufferStandardOutput(bool live) {
    static char buffer[1 << 20];
    if (live)
        std::setvbuf(stdout, nullptr, _IOLBF, 0);
    else
        std::setvbuf(stdout, buffer, _IOFBF, sizeof buffer);
}

// Text output has the capture's hints in its summary; jsonl's go to stderr.
void printJsonlHints(const DecodeArgs& a, const std::string& capture, const CaptureFacts& facts) {
    if (a.format != "jsonl") return;
    for (const auto& hint : facts.advice)
        printError(hintLine(capture, hint));
}

#if BUSDECODE_LIVE
LiveSettings liveSettings(const DecodeArgs& a) {
    LiveSettings s = parseDeviceSpec(a.device);
    if (!a.samplerate.empty()) {
        // "24M", "24 MHz" or "24000000", as sigrok-cli takes it.
        std::string text = a.samplerate;
        if (!text.empty() && std::string("kKMG").find(text.back()) != std::string::npos)
            text += "Hz";
        const SampleRate rate = parseSampleRate(text, true);
        if (!rate.timebase || rate.timebase->num != 1)
            throw InputError(fmt::format(
                "--samplerate {}: expected a whole number of Hz (24000000, 24M, 24 MHz)",
                a.samplerate));
        s.samplerate = std::uint64_t(rate.timebase->den);
    }
    if (!a.channels.empty())
        for (const auto& c : QString::fromStdString(a.channels).split(',', Qt::SkipEmptyParts)) {
            const std::string name = c.trimmed().toStdString();
            if (std::find(s.channels.begin(), s.channels.end(), name) != s.channels.end())
                throw InputError(fmt::format("--channels {}: {} is named twice", a.channels, name));
            s.channels.push_back(name);
        }
    if (!a.samples.empty()) {
        const auto n = parseInteger(a.samples);
        if (!n || *n < 1)
            throw InputError(
                fmt::format("--samples {}: expected a whole number, 1 or more", a.samples));
        s.samples = std::uint64_t(*n);
    }
    if (!a.seconds.empty()) {
        const auto t = parseNumber(a.seconds);
        // 1e7 s (116 days): past it, Ctrl-C (no --time) is what is meant.
        if (!t || !(*t > 0) || *t > 1e7)
            throw InputError(fmt::format(
                "--time {}: expected seconds, more than 0 and at most 1e7 (leave --time out to "
                "run until Ctrl-C)",
                a.seconds));
        s.seconds = *t;
    }
    s.save = a.save;
    return s;
}

int runLive(const DecodeArgs& a) {
    const LiveSettings settings = liveSettings(a);
    auto requests = buildRequests(a.protos, a.maps, a.opts);
    bufferStandardOutput(true);
    std::vector<NamedFile> inputs;
    for (const auto& [key, value] : settings.options)
        if (key == "file") inputs.push_back({"playback file", value});
    guardOutputs(a, inputs, {a.report});
    std::unique_ptr<OutputSink> lcm;
    if (a.lcm_url) lcm = makeLcmSink(*a.lcm_url, false);
    if (!a.report.empty()) checkWritable(a.report);
    const OutputSinks out(a, a.report, false, lcm.get());
    const CaptureFacts facts =
        liveModule("--device").decode(settings, requests, out.sinks, interruptionFlag());
    printJsonlHints(a, liveCaptureName(settings), facts);
    if (lcm) closeLcmSink(*lcm);
    return 0;
}

int runScan() {
    for (const auto& line : liveModule("--scan").scan())
        fmt::print("{}\n", line);
    return 0;
}
#else
int runLive(const DecodeArgs&) {
    throw InputError("--device: this decode was built without libsigrok");
}
int runScan() {
    throw InputError("--scan: this decode was built without libsigrok");
}
#endif

int runDecode(const DecodeArgs& a) {
    auto requests = buildRequests(a.protos, a.maps, a.opts);
    OpenOptions open;
    open.rate_hz = a.rate_hz;
    open.thresholds = a.thresholds;
    open.hysteresis = a.hysteresis;
    open.follow = a.follow;
    open.read_ahead = a.threads > 1;
    open.stop = interruptionFlag();
    bufferStandardOutput(a.follow || a.realtime || a.lcm_url);

    const std::vector<std::string> reports = a.report.empty()
                                                 ? std::vector<std::string>(a.captures.size())
                                                 : reportPaths(a.report, a.captures);
    guardOutputs(a, runInputs(a, a.captures), reports);
    std::unique_ptr<OutputSink> lcm;
    if (a.lcm_url) lcm = makeLcmSink(*a.lcm_url, a.captures.size() > 1);
    for (std::size_t i = 0; i < a.captures.size(); ++i) {
        const std::string& capture = a.captures[i];
        const OutputSinks out(a, reports[i], a.captures.size() > 1, lcm.get());
        const CaptureFacts facts =
            decodeCapture(capture, requests, open, out.sinks, a.realtime, interruptionFlag());
        printJsonlHints(a, capture, facts);
        if (interrupted()) break;  // a followed capture, ended by Ctrl-C
    }
    if (lcm) closeLcmSink(*lcm);
    return 0;
}

// "decode: FILE: interrupted, after reading N of M bytes (SIGINT); nothing written to the
// report"
std::string interruptionLine(const std::string& what, const DecodeArgs& a) {
    return fmt::format("decode: {} ({}){}\n", what, interruptingSignalName(),
                       a.report.empty() ? "" : "; nothing written to the report");
}

// Stopped by a signal before decoding began. A followed file whose header is still being
// written is not broken: the line says it was waiting, not what an unfinished header lacks.
int endInterrupted(const std::string& what, const DecodeArgs& a) {
    if (a.follow && a.captures.size() == 1)
        printError(
            fmt::format("decode: {}: stopped ({}) while following, before its header was "
                        "complete: nothing decoded\n",
                        oneLine(a.captures.front()), interruptingSignalName()));
    else
        printError(interruptionLine(what, a));
    return interruptedStatus();
}

int run(int argc, char** argv, DecodeArgs& args) {
    if (argc > 1 && std::string(argv[1]) == "monitor") return runMonitor(argc - 1, argv + 1);
    if (argc > 1 && std::string(argv[1]) == "merge-junit") return runMergeJunit(argc - 1, argv + 1);
    const bool verify = argc > 1 && std::string(argv[1]) == "verify";
    rememberRawArguments(argc, argv);
    QStringList argl = normaliseArgs(argc, argv);
    if (verify) argl.removeAt(1);
    Parsed parsed = parse(argl, verify);
    if (parsed.done) {
        checkStandardOutput();
        return 0;
    }
    args = parsed.args;
    if (parsed.formats) {
        const int status = runFormats(args);
        checkStandardOutput();
        return status;
    }
    if (parsed.scan) {
        const int status = runScan();
        checkStandardOutput();
        return status;
    }
    for (const auto& c : args.captures)
        if (c == "-" && standardStreams().stdin_closed)
            throw InputError("-: standard input is closed");
    // The decoders asked for (all of them to list them, or when none is named).
    loadPlugins(parsed.list ? std::vector<std::string>{} : args.protos);
    if (parsed.list) {
        printDecoderList(stdout);
        checkStandardOutput();
        return 0;
    }
    if (verify) return runVerify(args);  // checks stdout before writing its JUnit file
    const int status = args.device.empty() ? runDecode(args) : runLive(args);
    checkStandardOutput();
    return status;
}

}  // namespace

int runCli(int argc, char** argv) {
    // Before Qt opens its first descriptor.
    guardStandardStreams();
    catchInterruptions();
    QCoreApplication app(argc, argv);
    DecodeArgs args;
    int status = 2;
    try {
        status = run(argc, argv, args);
    } catch (const Interrupted& e) {
        std::fflush(stdout);
        return endInterrupted(e.what(), args);
    } catch (const InputError& e) {
        std::fflush(stdout);
        // Interrupted while opening or reading: the error is the interruption's doing.
        if (interrupted())
            return endInterrupted(fmt::format("interrupted: {}", oneLine(e.what())), args);
        printError(fmt::format("decode: {}\n", oneLine(e.what())));
        return 2;
    } catch (const std::system_error& e) {
        // fmt::print's, writing help or the decoder list to a stdout that fails.
        const bool out = std::ferror(stdout);
        printError(fmt::format("decode: {}{}\n", out ? "standard output: cannot write: " : "",
                               out ? e.code().message() : e.what()));
        return 2;
    } catch (const std::exception& e) {
        std::fflush(stdout);
        printError(fmt::format("decode: internal error: {}\n", oneLine(e.what())));
        return 2;
    }
    return standardErrorFailed() && status == 0 ? 2 : status;
}

}  // namespace busdecode
