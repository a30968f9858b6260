#include "event_columns.h"

#include <bit>
#include <cmath>
#include <limits>

#include "sinks/event_format.h"

namespace busdecode::py {

void Column::appendNull() {
    if (kind == Kind::Object) {
        objects.emplace_back(Null{});
        return;
    }
    lanes.push_back(0);
    nulls.push_back(1);
}

void Column::dropLast() {
    if (kind == Kind::Object) {
        objects.pop_back();
        return;
    }
    lanes.pop_back();
    nulls.pop_back();
}

void Column::appendText(const std::string& s) {
    if (last_text_ < texts.size() && texts[last_text_] == s)
        return appendNumber(Kind::Text, last_text_);
    auto it = text_codes_.find(s);
    if (it == text_codes_.end()) {
        it = text_codes_.emplace(s, texts.size()).first;
        texts.push_back(s);
    }
    last_text_ = it->second;
    appendNumber(Kind::Text, it->second);
}

void Column::toReal() {
    for (std::size_t i = 0; i < lanes.size(); ++i)
        if (!nulls[i])
            lanes[i] = std::bit_cast<std::uint64_t>(
                kind == Kind::UInt ? double(lanes[i]) : double(std::int64_t(lanes[i])));
    kind = Kind::Real;
}

void Column::toObjects() {
    objects.reserve(lanes.size() + 1);
    for (std::size_t i = 0; i < lanes.size(); ++i) {
        const std::uint64_t b = lanes[i];
        if (nulls[i])
            objects.emplace_back(Null{});
        else if (kind == Kind::Bool)
            objects.emplace_back(b != 0);
        else if (kind == Kind::UInt)
            objects.emplace_back(b);
        else if (kind == Kind::Real)
            objects.emplace_back(std::bit_cast<double>(b));
        else if (kind == Kind::Text)
            objects.emplace_back(texts[b]);
        else
            objects.emplace_back(std::int64_t(b));
    }
    lanes = {};
    nulls = {};
    texts = {};
    text_codes_ = {};
    kind = Kind::Object;
}

void Column::appendAnyKind(const Value& v) {
    if (kind == Kind::Object) {
        objects.push_back(v);
        return;
    }
    if (auto b = std::get_if<bool>(&v)) {
        if (kind == Kind::Empty || kind == Kind::Bool) return appendNumber(Kind::Bool, *b);
    } else if (auto i = std::get_if<std::int64_t>(&v)) {
        if (kind == Kind::Real) return appendNumber(kind, std::bit_cast<std::uint64_t>(double(*i)));
        if (kind == Kind::Empty || kind == Kind::Int || (kind == Kind::UInt && *i >= 0)) {
            negative = negative || *i < 0;
            return appendNumber(Kind::Int, std::uint64_t(*i));
        }
    } else if (auto u = std::get_if<std::uint64_t>(&v)) {
        if (kind == Kind::Real) return appendNumber(kind, std::bit_cast<std::uint64_t>(double(*u)));
        const bool big = *u > std::uint64_t(std::numeric_limits<std::int64_t>::max());
        if (kind == Kind::Empty || kind == Kind::Int || kind == Kind::UInt) {
            if (!big) return appendNumber(kind == Kind::UInt ? kind : Kind::Int, *u);
            if (!negative) {
                kind = Kind::UInt;
                return appendNumber(kind, *u);
            }
        }
    } else if (auto d = std::get_if<double>(&v)) {
        if (kind == Kind::Int || kind == Kind::UInt) toReal();
        if (kind == Kind::Empty || kind == Kind::Real)
            return appendNumber(Kind::Real, std::bit_cast<std::uint64_t>(*d));
    } else if (auto t = std::get_if<std::string>(&v)) {
        if (kind == Kind::Empty || kind == Kind::Text) return appendText(*t);
    } else if (isNull(v)) {
        return appendNull();
    }
    toObjects();
    objects.push_back(v);
}

[[gnu::always_inline]] inline std::size_t Table::columnFor(const std::string& key,
                                                           std::size_t position) {
    if (const std::size_t* column = last_order_.find(key, position)) return *column;
    return findColumn(key, position);
}

std::size_t Table::findColumn(const std::string& key, std::size_t position) {
    if (isCommonEventKey(key)) return kNoColumn;
    auto it = index_.find(key);
    if (it == index_.end()) {
        Column c;
        c.key = key;
        for (std::size_t r = 0; r < start_ns.size(); ++r)
            c.appendNull();
        columns.push_back(std::move(c));
        it = index_.emplace(key, columns.size() - 1).first;
    }
    return last_order_.remember(key, position, it->second);
}

std::uint32_t Table::errorSet(const std::vector<std::string>& errs) {
    if (errs.empty()) return 0;
    auto it = error_index_.find(errs);
    if (it != error_index_.end()) return it->second;
    error_sets.push_back(errs);
    const auto id = std::uint32_t(error_sets.size() - 1);
    error_index_.emplace(errs, id);
    return id;
}

void Table::add(const Event& e, std::int64_t start, std::int64_t end) {
    const std::size_t row = start_ns.size();
    std::size_t position = 0;
    for (const auto& f : e.fields) {
        const std::size_t column = columnFor(f.key, position);
        if (column == kNoColumn) continue;
        ++position;
        Column& c = columns[column];
        if (c.rows() > row) c.dropLast();  // a key given twice: JSON readers keep the last
        c.append(f.value);
    }
    for (auto& c : columns)
        if (c.rows() == row) c.appendNull();
    start_ns.push_back(start);
    end_ns.push_back(end);
    errors.push_back(errorSet(e.errors));
}

void TableSink::onEvent(const Event& e, const CaptureFacts& facts) {
    if (!last_ || last_->proto != e.proto || last_->type != e.type) {
        const std::string key = e.proto + "/" + e.type;
        auto it = index_.find(key);
        if (it == index_.end()) {
            tables.push_back({});
            tables.back().proto = e.proto;
            tables.back().type = e.type;
            it = index_.emplace(key, tables.size() - 1).first;
        }
        last_ = &tables[it->second];
    }
    last_->add(e, facts.timebase.toNs(e.start), facts.timebase.toNs(e.end));
}

}  // namespace busdecode::py
