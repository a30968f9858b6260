#include "event_expect.h"

#include <fmt/format.h>

#include "core/registry.h"
#include "spi_info.h"
#include "tmc8100_decoder.h"

#ifdef BUSDECODE_HAVE_SSI
namespace busdecode {
std::shared_ptr<const DecoderFactory> makeSsiFactory();
}
#endif
#ifdef BUSDECODE_HAVE_BISSC
namespace busdecode {
std::shared_ptr<const DecoderFactory> makeBisscFactory();
}
#endif

namespace busdecode::test {

Value I(std::int64_t v) {
    return v;
}
Value S(const char* s) {
    return std::string(s);
}

std::string show(const Value& v) {
    return std::visit(
        [](const auto& x) -> std::string {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, Null>)
                return "null";
            else if constexpr (std::is_same_v<T, bool>)
                return x ? "true" : "false";
            else if constexpr (std::is_same_v<T, std::string>)
                return "\"" + x + "\"";
            else if constexpr (std::is_same_v<T, std::vector<std::int64_t>>)
                return "[list]";
            else
                return fmt::format("{}", x);
        },
        v);
}

std::vector<Event> only(const std::vector<Event>& events, const std::string& proto,
                        const std::string& type) {
    std::vector<Event> out;
    for (const auto& e : events)
        if (e.proto == proto && (type.empty() || e.type == type)) out.push_back(e);
    return out;
}

void expectEvents(const std::vector<Event>& events, const std::string& proto,
                  const std::vector<Expected>& want) {
    const auto got = only(events, proto);
    EXPECT_EQ(got.size(), want.size()) << "number of " << proto << " events";
    for (std::size_t i = 0; i < std::min(got.size(), want.size()); ++i) {
        const Event& e = got[i];
        const Expected& w = want[i];
        SCOPED_TRACE(fmt::format("{} event #{} ({}: {})", proto, i, e.type, e.summary));
        EXPECT_EQ(e.type, w.type);
        EXPECT_EQ(e.start, w.start);
        EXPECT_EQ(e.end, w.end);
        for (const auto& [k, v] : w.fields) {
            const Value* got_v = e.get(k);
            if (!got_v) {
                ADD_FAILURE() << "missing field " << k;
                continue;
            }
            EXPECT_EQ(show(*got_v), show(v)) << "field " << k;
        }
        EXPECT_EQ(e.errors, w.errors);
    }
}

void registerDecoders() {
    Registry::instance().add(makeSpiFactory());
    Registry::instance().add(makeTmc8100Factory());
#ifdef BUSDECODE_HAVE_SSI
    Registry::instance().add(makeSsiFactory());
#endif
#ifdef BUSDECODE_HAVE_BISSC
    Registry::instance().add(makeBisscFactory());
#endif
}

}  // namespace busdecode::test
