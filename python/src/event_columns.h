#pragma once
// read(): a capture's events as columns, one table per proto/type, built while they
// stream by (an OutputSink on the decoding thread, no Python): numbers in flat 64-bit
// lanes with a null mask, so that the DataFrame's columns are made from buffers and not
// from a Python object per field.
#include <bit>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/session.h"
#include "field_order.h"
#include "lane_buffer.h"

namespace busdecode::py {

// One field of one table. Numbers stay in `lanes` as long as every value fits one kind,
// strings as codes into the column's distinct strings; anything else (lists, a mix of
// kinds) makes it a column of Values.
struct Column {
    enum class Kind { Empty, Bool, Int, UInt, Real, Text, Object };
    std::string key;
    Kind kind = Kind::Empty;
    LaneBuffer<std::uint64_t> lanes;  // int64 / uint64 / double bits / 0-1, per row
    LaneBuffer<std::uint8_t> nulls;   // 1 where the row has no value
    std::vector<Value> objects;       // Kind::Object: every row
    std::vector<std::string> texts;   // Kind::Text: the distinct strings, by code
    bool negative = false;            // an int64 below 0 was seen

    std::size_t rows() const { return kind == Kind::Object ? objects.size() : nulls.size(); }
    void append(const Value& v) {
        // The common case inline: a value of the column's own kind.
        if (kind == Kind::Int && std::holds_alternative<std::int64_t>(v)) {
            const std::int64_t i = *std::get_if<std::int64_t>(&v);
            negative = negative || i < 0;
            return appendNumber(kind, std::uint64_t(i));
        }
        if (kind == Kind::Bool && std::holds_alternative<bool>(v))
            return appendNumber(kind, *std::get_if<bool>(&v));
        if (kind == Kind::Real && std::holds_alternative<double>(v))
            return appendNumber(kind, std::bit_cast<std::uint64_t>(*std::get_if<double>(&v)));
        appendAnyKind(v);
    }
    void appendNull();
    void dropLast();

private:
    void appendAnyKind(const Value& v);  // with the promotions between kinds
    void appendNumber(Kind k, std::uint64_t bits) {
        if (kind == Kind::Empty) kind = k;
        lanes.push_back(bits);
        nulls.push_back(0);
    }
    void appendText(const std::string& s);
    std::unordered_map<std::string, std::uint64_t> text_codes_;
    std::uint64_t last_text_ = 0;  // the code appended last: most rows repeat it
    void toReal();
    void toObjects();
};

struct Table {
    std::string proto, type;
    LaneBuffer<std::int64_t> start_ns, end_ns;
    std::vector<Column> columns;  // in the order the fields first appeared
    // Each row's errors as an index into the distinct error lists seen (0: none).
    LaneBuffer<std::uint32_t> errors;
    std::vector<std::vector<std::string>> error_sets{{}};

    void add(const Event& e, std::int64_t start, std::int64_t end);

private:
    // The column of the field at `position` among the event's own fields (made when
    // new); kNoColumn for a key every event has (proto, start_ns...), kept apart.
    std::size_t columnFor(const std::string& key, std::size_t position);
    static constexpr std::size_t kNoColumn = ~std::size_t(0);
    [[gnu::noinline]] std::size_t findColumn(const std::string& key, std::size_t position);
    std::uint32_t errorSet(const std::vector<std::string>& errors);
    std::unordered_map<std::string, std::size_t> index_;
    FieldOrder<std::size_t> last_order_;  // the column of each field position
    std::map<std::vector<std::string>, std::uint32_t> error_index_;
};

class TableSink : public OutputSink {
public:
    void begin(const CaptureFacts& facts) override { capture_start = facts.capture_start; }
    void onEvent(const Event& e, const CaptureFacts& facts) override;
    bool readsSummaries() const override { return false; }  // columns are the fields
    // Tables by "proto/type", in the order their first events came.
    std::vector<Table> tables;
    std::string capture_start;  // every row's, as jsonl has it on every line ("": none)

private:
    std::unordered_map<std::string, std::size_t> index_;
    Table* last_ = nullptr;
};

}  // namespace busdecode::py
