// The rules-file parser: arbitrary text must parse or give an InputError naming the
// file (and a line), never anything else.
#include <string>

#include "core/options.h"
#include "fuzz_harness.h"
#include "reader_targets.h"
#ifdef FUZZ_HAVE_RULES
#include "verify/rules.h"
#endif

namespace busdecode::fuzz {

void runRulesTarget(const std::uint8_t* data, std::size_t size) {
#ifdef FUZZ_HAVE_RULES
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::string file = "rules.toml";
    try {
        Rules r = parseRules(text, file, {"ssi", "bissc", "spi", "tmc8100", "uart", "tmcl"});
        for (const auto& t : r.tables)
            if (t.proto.empty()) throw HarnessFailure("a rules table without a name");
    } catch (const InputError& e) {
        const std::string msg = e.what();
        if (msg.rfind(file, 0) != 0)
            throw HarnessFailure("rules error does not start with the file name: " + msg);
        if (msg.find('\n') != std::string::npos)
            throw HarnessFailure("rules error is not one line: " + msg);
    } catch (const HarnessFailure&) {
        throw;
    } catch (const std::exception& e) {
        throw HarnessFailure(std::string("rules parser threw something else: ") + e.what());
    }
#else
    (void)data;
    (void)size;
    throw HarnessFailure("the rules parser (analyzer/verify) is not built in");
#endif
}

}  // namespace busdecode::fuzz
