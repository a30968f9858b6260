#include "fuzz_harness.h"

#include <memory>

#include "core/registry.h"
#include "reader_targets.h"
#include "vcd_pieces.h"

namespace busdecode {
// The decoders' factories (each decoder's own header declares its one).
#define BUSDECODE_FUZZ_FACTORY(fn) std::shared_ptr<const DecoderFactory> fn();
#ifdef FUZZ_HAVE_SPI
BUSDECODE_FUZZ_FACTORY(makeSpiFactory)
#endif
#ifdef FUZZ_HAVE_BISSC
BUSDECODE_FUZZ_FACTORY(makeBisscFactory)
#endif
#ifdef FUZZ_HAVE_SSI
BUSDECODE_FUZZ_FACTORY(makeSsiFactory)
#endif
#ifdef FUZZ_HAVE_TMC8100
BUSDECODE_FUZZ_FACTORY(makeTmc8100Factory)
#endif
#ifdef FUZZ_HAVE_UART
BUSDECODE_FUZZ_FACTORY(makeUartFactory)
#endif
#ifdef FUZZ_HAVE_TMCL
BUSDECODE_FUZZ_FACTORY(makeTmclFactory)
#endif
#undef BUSDECODE_FUZZ_FACTORY
}  // namespace busdecode

namespace busdecode::fuzz {

void registerDecoders() {
    static const bool done = [] {
        auto& r = Registry::instance();
#ifdef FUZZ_HAVE_SPI
        r.add(makeSpiFactory());
#endif
#ifdef FUZZ_HAVE_BISSC
        r.add(makeBisscFactory());
#endif
#ifdef FUZZ_HAVE_SSI
        r.add(makeSsiFactory());
#endif
#ifdef FUZZ_HAVE_TMC8100
        r.add(makeTmc8100Factory());
#endif
#ifdef FUZZ_HAVE_UART
        r.add(makeUartFactory());
#endif
#ifdef FUZZ_HAVE_TMCL
        r.add(makeTmclFactory());
#endif
        (void)r;
        return true;
    }();
    (void)done;
}

std::vector<std::string> targetNames() {
    std::vector<std::string> out = {"vcd",        "vcd_pieces",  "csv_sigrok", "csv_saleae",
                                    "csv_plain",  "sr",          "cli_args",   "dsl",
                                    "compressed", "sample_rows", "saleae_bin", "fst"};
#ifdef FUZZ_HAVE_RULES
    out.push_back("rules");
#endif
    registerDecoders();
    for (const auto* f : Registry::instance().all())
        out.push_back("decoder_" + f->info().id);
    return out;
}

void runTarget(const std::string& target, const std::uint8_t* data, std::size_t size) {
    if (target == "vcd" || target == "csv_sigrok" || target == "csv_saleae")
        return runReaderTarget(ReaderKind::Text, data, size);
    if (target == "vcd_pieces") return runVcdPiecesTarget(data, size);
    if (target == "csv_plain") return runReaderTarget(ReaderKind::PlainCsv, data, size);
    if (target == "sr") return runReaderTarget(ReaderKind::Sr, data, size);
    if (target == "dsl") return runReaderTarget(ReaderKind::Dsl, data, size);
    // Compressed streams are the file's bytes; rows need the rate a plain CSV needs.
    if (target == "compressed" || target == "saleae_bin" || target == "fst")
        return runReaderTarget(ReaderKind::Text, data, size);
    if (target == "sample_rows") return runReaderTarget(ReaderKind::PlainCsv, data, size);
    if (target == "rules") return runRulesTarget(data, size);
    if (target == "cli_args") return runCliArgsTarget(data, size);
    if (target.rfind("decoder_", 0) == 0) return runDecoderTarget(target.substr(8), data, size);
    throw HarnessFailure("unknown fuzz target '" + target + "'");
}

}  // namespace busdecode::fuzz
