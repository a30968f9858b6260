// decode() and follow(): the Python iterator over an EventStream, and decoders().
#include <pybind11/stl.h>

#include <memory>

#include "app/list_decoders.h"
#include "app/plugin_loader.h"
#include "bindings.h"
#include "core/registry.h"
#include "decode_args_py.h"
#include "event_dict.h"
#include "event_stream.h"

namespace busdecode::py {

namespace {

constexpr int kPollMs = 100;         // how often a wait looks at Ctrl-C
constexpr std::size_t kBatch = 512;  // events handed over at a time from a file

pyb::dict factsToPython(const CaptureFacts& f) {
    pyb::list bindings;
    for (const auto& b : f.bindings)
        bindings.append(pyb::dict(pyb::arg("proto") = b.proto, pyb::arg("instance") = b.instance,
                                  pyb::arg("role") = b.role, pyb::arg("signal") = b.signal));
    return pyb::dict(pyb::arg("file") = pathToPython(f.file), pyb::arg("format") = f.format,
                     pyb::arg("capture_start") = textToPython(f.capture_start),
                     pyb::arg("ns_per_tick") = f.timebase.nsPerTick(),
                     pyb::arg("protos") = f.protos, pyb::arg("bindings") = bindings,
                     pyb::arg("edges") = f.edges, pyb::arg("advice") = f.advice);
}

class Events {
public:
    Events(DecodeJob job, bool live)
        : stream_(std::make_unique<EventStream>(std::move(job), live ? 1 : kBatch)) {
        waitInterruptibly([&] { return stream_->waitStarted(kPollMs); }, [&] { stream_.reset(); });
        dict_.setCaptureStart(stream_->facts().capture_start);
    }
    ~Events() { close(); }

    pyb::dict next() {
        // As a generator: one reader at a time (the wait below releases the GIL).
        if (busy_) throw pyb::value_error("decode(): already being read on another thread");
        while (at_ >= batch_.size()) {
            if (!stream_) throw pyb::stop_iteration();
            // list(decode(...)) iterates in C, where Python checks for Ctrl-C never.
            if (PyErr_CheckSignals() != 0) throw pyb::error_already_set();
            at_ = 0;  // next() takes the batch back
            EventStream::Got got = EventStream::Got::Waiting;
            busy_ = true;
            try {
                waitInterruptibly(
                    [&] {
                        got = stream_->next(batch_, kPollMs);
                        return got != EventStream::Got::Waiting;
                    },
                    [&] { stream_.reset(); });
            } catch (...) {
                busy_ = false;
                if (closing_) close();
                throw;
            }
            busy_ = false;
            if (closing_) {  // close() came from another thread while this one waited
                close();
                throw pyb::stop_iteration();
            }
            if (got == EventStream::Got::End) {
                facts_ = stream_->facts();
                close();
                throw pyb::stop_iteration();
            }
        }
        return dict_(batch_[at_++]);
    }
    void close() {
        if (busy_) {  // another thread waits in next(), filling batch_: it ends the iteration
            closing_ = true;
            if (stream_) stream_->stop();
            return;
        }
        batch_.clear();
        at_ = 0;
        if (!stream_) return;
        // Taken out with the GIL held: another thread's next() then sees no stream.
        std::unique_ptr<EventStream> stream = std::move(stream_);
        facts_ = stream->facts();
        withoutGil([&] { stream.reset(); }, [] {});  // stops the decode, joins its thread
    }
    pyb::dict facts() { return factsToPython(stream_ ? stream_->facts() : facts_); }

private:
    std::unique_ptr<EventStream> stream_;
    std::vector<TimedEvent> batch_;
    std::size_t at_ = 0;
    bool busy_ = false;     // next() waits with the GIL released
    bool closing_ = false;  // close() while busy_: next() closes when it wakes
    DictMaker dict_;
    CaptureFacts facts_;
};

pyb::list decoderList() {
    loadPlugins();
    pyb::list out;
    for (const auto* f : Registry::instance().all()) {
        const DecoderInfo& d = f->info();
        pyb::list roles, options, events;
        for (const auto& r : d.roles)
            roles.append(pyb::dict(pyb::arg("name") = r.name, pyb::arg("required") = r.required,
                                   pyb::arg("aliases") = r.aliases, pyb::arg("help") = r.help));
        for (const auto& o : d.options) {
            pyb::object lo = o.min > -1e299 ? pyb::object(pyb::float_(o.min)) : pyb::none();
            pyb::object hi = o.max < 1e299 ? pyb::object(pyb::float_(o.max)) : pyb::none();
            options.append(
                pyb::dict(pyb::arg("key") = o.key, pyb::arg("kind") = optionKindName(o.kind),
                          pyb::arg("default") = o.default_value, pyb::arg("choices") = o.choices,
                          pyb::arg("min") = lo, pyb::arg("max") = hi,
                          pyb::arg("auto") = o.allow_auto, pyb::arg("help") = o.help));
        }
        for (const auto& e : d.events) {
            pyb::list fields;
            pyb::dict kinds;
            for (const auto& f : e.fields) {
                fields.append(f.name);
                kinds[pyb::str(f.name)] = fieldKindName(f.kind);
            }
            events.append(pyb::dict(pyb::arg("type") = e.type, pyb::arg("help") = e.help,
                                    pyb::arg("fields") = fields, pyb::arg("kinds") = kinds));
        }
        out.append(pyb::dict(pyb::arg("id") = d.id, pyb::arg("name") = d.name,
                             pyb::arg("description") = d.description, pyb::arg("roles") = roles,
                             pyb::arg("options") = options, pyb::arg("events") = events,
                             pyb::arg("need_one_of") = d.need_one_of));
    }
    return out;
}

}  // namespace

void bindDecoders(pyb::module_& m) {
    m.def("decoders", &decoderList, "Every decoder's declaration, as `decode --list` shows it.");
}

void bindDecode(pyb::module_& m) {
    pyb::class_<Events>(m, "Events", "Events of one capture as they are decoded.")
        .def("__iter__", [](Events& e) -> Events& { return e; })
        .def("__next__", &Events::next)
        .def("close", &Events::close, "Stops decoding; the iterator then ends.")
        .def("__enter__", [](Events& e) -> Events& { return e; })
        .def("__exit__", [](Events& e, pyb::args) { e.close(); })
        .def_property_readonly("facts", &Events::facts,
                               "The capture: file, format, bindings, and at the end edges and "
                               "the decoders' advice.");
    m.def(
        "decode_events",
        [](CaptureArgs a, bool follow, bool realtime) {
            DecodeJob job = jobFor(a, follow);
            job.realtime = realtime;
            return std::make_unique<Events>(std::move(job), follow || realtime);
        },
        pyb::arg("args"), pyb::arg("follow"), pyb::arg("realtime"));
    pyb::class_<CaptureArgs>(m, "CaptureArgs")
        .def(pyb::init<>())
        .def_readwrite("path", &CaptureArgs::path)
        .def_readwrite("protos", &CaptureArgs::protos)
        .def_readwrite("maps", &CaptureArgs::maps)
        .def_readwrite("opts", &CaptureArgs::opts)
        .def_readwrite("rate", &CaptureArgs::rate)
        .def_readwrite("thresholds", &CaptureArgs::thresholds)
        .def_readwrite("hysteresis", &CaptureArgs::hysteresis)
        .def_readwrite("threads", &CaptureArgs::threads);
}

}  // namespace busdecode::py
