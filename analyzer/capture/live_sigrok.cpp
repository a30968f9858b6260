// libsigrok 0.5 through its C API (the C++ bindings would add glibmm for nothing more).
// Everything but run() happens on the caller's thread; run() starts the session on its
// own thread, where libsigrok then delivers the data feed.
#include "live_sigrok.h"

#include <glib.h>
#include <libsigrok/libsigrok.h>

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "capture/capture_writer.h"
#include "core/options.h"

namespace busdecode {

namespace {

// libsigrok logs through one global callback: its last error is kept to explain ours,
// and nothing of it reaches stderr (our errors are one line).
std::mutex g_log_mu;
std::string g_last_error;

int keepLastError(void*, int level, const char* format, va_list args) {
    if (level > SR_LOG_ERR) return SR_OK;
    char text[512];
    std::vsnprintf(text, sizeof text, format, args);
    std::lock_guard lock(g_log_mu);
    g_last_error = text;
    return SR_OK;
}

std::string lastError() {
    std::lock_guard lock(g_log_mu);
    return g_last_error;
}

// " (libsigrok: TEXT)" or "".
std::string becauseOf() {
    const std::string e = lastError();
    return e.empty() ? "" : " (libsigrok: " + e + ")";
}

struct Context {
    sr_context* ctx = nullptr;
    Context() {
        sr_log_callback_set(keepLastError, nullptr);
        sr_log_loglevel_set(SR_LOG_ERR);
        if (sr_init(&ctx) != SR_OK) throw InputError("libsigrok: cannot initialise");
    }
    ~Context() {
        if (ctx) sr_exit(ctx);
    }
};

sr_dev_driver* findDriver(sr_context* ctx, const std::string& name) {
    sr_dev_driver** drivers = sr_driver_list(ctx);
    for (int i = 0; drivers && drivers[i]; ++i)
        if (name == drivers[i]->name) return drivers[i];
    return nullptr;
}

// The scan options a --device may carry (conn=..., serialcomm=...); a GSList of sr_config.
GSList* scanOptions(const LiveSettings& s) {
    GSList* list = nullptr;
    for (const auto& [key, value] : s.options) {
        std::uint32_t k = 0;
        if (key == "conn")
            k = SR_CONF_CONN;
        else if (key == "serialcomm")
            k = SR_CONF_SERIALCOMM;
        else
            throw InputError(fmt::format("--device {}: unknown option '{}' (conn, serialcomm)",
                                         liveCaptureName(s), key));
        auto* c = g_new0(sr_config, 1);
        c->key = k;
        c->data = g_variant_ref_sink(g_variant_new_string(value.c_str()));
        list = g_slist_append(list, c);
    }
    return list;
}

void freeScanOptions(GSList* list) {
    for (GSList* l = list; l; l = l->next) {
        auto* c = static_cast<sr_config*>(l->data);
        g_variant_unref(c->data);
        g_free(c);
    }
    g_slist_free(list);
}

std::string channelList(GSList* channels, int type) {
    std::vector<std::string> names;
    for (GSList* l = channels; l; l = l->next) {
        auto* ch = static_cast<sr_channel*>(l->data);
        if (ch->type == type) names.push_back(ch->name);
    }
    return fmt::format("{}", fmt::join(names, " "));
}

// The rates a device offers, as text, and whether `hz` is one of them (true when the
// device does not say).
bool offersRate(const sr_dev_inst* sdi, std::uint64_t hz, std::string& offered) {
    GVariant* list = nullptr;
    if (sr_config_list(sr_dev_inst_driver_get(sdi), sdi, nullptr, SR_CONF_SAMPLERATE, &list) !=
            SR_OK ||
        !list)
        return true;
    bool ok = true;
    gsize n = 0;
    if (GVariant* steps = g_variant_lookup_value(list, "samplerate-steps", G_VARIANT_TYPE("at"))) {
        const auto* v = static_cast<const guint64*>(g_variant_get_fixed_array(steps, &n, 8));
        if (n >= 3) {
            ok = hz >= v[0] && hz <= v[1] && (v[2] <= 1 || (hz - v[0]) % v[2] == 0);
            offered = fmt::format("{} to {} in steps of {}", sampleRateText(std::int64_t(v[0])),
                                  sampleRateText(std::int64_t(v[1])), v[2]);
        }
        g_variant_unref(steps);
    } else if (GVariant* rates =
                   g_variant_lookup_value(list, "samplerates", G_VARIANT_TYPE("at"))) {
        const auto* v = static_cast<const guint64*>(g_variant_get_fixed_array(rates, &n, 8));
        std::vector<std::string> texts;
        for (gsize i = 0; i < n; ++i)
            texts.push_back(sampleRateText(std::int64_t(v[i])));
        ok = std::find(v, v + n, hz) != v + n;
        offered = fmt::format("{}", fmt::join(texts, ", "));
        g_variant_unref(rates);
    }
    g_variant_unref(list);
    return ok;
}

}  // namespace

struct SigrokAcquisition::Impl {
    LiveSettings settings;
    Context context;
    sr_session* session = nullptr;
    sr_dev_inst* sdi = nullptr;
    bool playback = false;
    bool opened = false;  // sr_dev_open succeeded (a hardware device to close)
    std::vector<std::string> names;
    std::uint64_t rate = 0;
    std::atomic<bool> stop_requested{false};
    std::atomic<bool> stop_sent{false};  // sr_session_stop() called from the data feed
    const LogicPacket* on_logic = nullptr;
    std::uint64_t delivered = 0;  // samples, for pacing a playback
    std::chrono::steady_clock::time_point t0;

    std::string name() const { return liveCaptureName(settings); }
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(fmt::format("--device {}: {}", name(), what));
    }

    void openPlayback();
    void openHardware();
    void chooseChannels();
    void chooseRate();
    void onPacket(const sr_datafeed_packet* p);
    void pace();

    ~Impl() {
        if (session) sr_session_destroy(session);
        if (opened) sr_dev_close(sdi);
    }
};

void SigrokAcquisition::Impl::openPlayback() {
    playback = true;
    std::string file;
    for (const auto& [key, value] : settings.options) {
        if (key != "file") fail(fmt::format("unknown option '{}' (file)", key));
        file = value;
    }
    if (file.empty()) fail("expected playback:file=CAPTURE.sr");
    if (sr_session_load(context.ctx, file.c_str(), &session) != SR_OK)
        throw InputError(
            fmt::format("{}: cannot play back: not a sigrok session{}", file, becauseOf()));
    GSList* devices = nullptr;
    sr_session_dev_list(session, &devices);
    if (!devices) throw InputError(fmt::format("{}: cannot play back: no device in it", file));
    sdi = static_cast<sr_dev_inst*>(devices->data);
    g_slist_free(devices);
}

void SigrokAcquisition::Impl::openHardware() {
    sr_dev_driver* driver = findDriver(context.ctx, settings.driver);
    if (!driver) fail("no such libsigrok driver (decode --scan lists the attached devices)");
    if (sr_driver_init(context.ctx, driver) != SR_OK)
        fail("cannot initialise the driver" + becauseOf());
    GSList* options = scanOptions(settings);
    GSList* found = sr_driver_scan(driver, options);
    freeScanOptions(options);
    if (!found) fail("no device found (connected? permissions?)" + becauseOf());
    sdi = static_cast<sr_dev_inst*>(found->data);
    g_slist_free(found);
    if (sr_dev_open(sdi) != SR_OK) fail("cannot open the device (permissions?)" + becauseOf());
    opened = true;
    if (sr_session_new(context.ctx, &session) != SR_OK || sr_session_dev_add(session, sdi) != SR_OK)
        fail("cannot start a session" + becauseOf());
}

void SigrokAcquisition::Impl::chooseChannels() {
    GSList* channels = sr_dev_inst_channels_get(sdi);
    for (const auto& wanted : settings.channels) {
        bool known = false;
        for (GSList* l = channels; l; l = l->next) {
            auto* ch = static_cast<sr_channel*>(l->data);
            known |= ch->type == SR_CHANNEL_LOGIC && wanted == ch->name;
        }
        if (!known)
            throw InputError(fmt::format("--channels {}: {} has no logic channel {} (channels: {})",
                                         wanted, name(), wanted,
                                         channelList(channels, SR_CHANNEL_LOGIC)));
    }
    // Logic packets keep each channel at its index's bit: names are listed by index.
    std::vector<std::pair<int, std::string>> enabled;
    for (GSList* l = channels; l; l = l->next) {
        auto* ch = static_cast<sr_channel*>(l->data);
        bool on = ch->type == SR_CHANNEL_LOGIC &&
                  (settings.channels.empty()
                       ? (!playback || ch->enabled)
                       : std::count(settings.channels.begin(), settings.channels.end(), ch->name));
        if (!playback) sr_dev_channel_enable(ch, on);
        if (on) enabled.emplace_back(ch->index, ch->name);
    }
    if (enabled.empty()) fail("no logic channel to acquire");
    std::sort(enabled.begin(), enabled.end());
    if (enabled.back().first >= 64) fail("logic channels beyond the 64th are not supported");
    // A channel's bit is its index; a gap (a disabled channel) keeps its place unnamed.
    names.assign(std::size_t(enabled.back().first) + 1, "");
    for (const auto& [index, n] : enabled)
        names[std::size_t(index)] = n;
}

void SigrokAcquisition::Impl::chooseRate() {
    const sr_dev_driver* driver = sr_dev_inst_driver_get(sdi);
    if (settings.samplerate && !playback) {
        std::string offered;
        if (!offersRate(sdi, settings.samplerate, offered) ||
            sr_config_set(sdi, nullptr, SR_CONF_SAMPLERATE,
                          g_variant_new_uint64(settings.samplerate)) != SR_OK)
            throw InputError(fmt::format("--samplerate {}: not supported by {}{}",
                                         settings.samplerate, name(),
                                         offered.empty() ? "" : " (it offers " + offered + ")"));
    }
    GVariant* v = nullptr;
    if (sr_config_get(driver, sdi, nullptr, SR_CONF_SAMPLERATE, &v) == SR_OK && v) {
        rate = g_variant_get_uint64(v);
        g_variant_unref(v);
    }
    if (rate == 0) fail("the device does not say its sample rate");
    if (playback && settings.samplerate && settings.samplerate != rate)
        throw InputError(fmt::format("--samplerate {}: the session was recorded at {} Hz",
                                     settings.samplerate, rate));
}

SigrokAcquisition::SigrokAcquisition(const LiveSettings& settings)
    : impl_(std::make_unique<Impl>()) {
    impl_->settings = settings;
    if (settings.driver == "playback")
        impl_->openPlayback();
    else
        impl_->openHardware();
    impl_->chooseChannels();
    impl_->chooseRate();
}

SigrokAcquisition::~SigrokAcquisition() = default;

const std::vector<std::string>& SigrokAcquisition::channelNames() const {
    return impl_->names;
}
std::uint64_t SigrokAcquisition::samplerate() const {
    return impl_->rate;
}
bool SigrokAcquisition::isPlayback() const {
    return impl_->playback;
}
std::string SigrokAcquisition::lastLibraryError() const {
    return lastError();
}

// A recorded session runs no faster than it was recorded; a stop ends the wait at once.
void SigrokAcquisition::Impl::pace() {
    using namespace std::chrono;
    const auto due = t0 + duration_cast<steady_clock::duration>(
                              duration<double>(double(delivered) / double(rate)));
    while (!stop_requested) {
        const auto now = steady_clock::now();
        if (now >= due) return;
        std::this_thread::sleep_for(std::min<steady_clock::duration>(due - now, milliseconds(20)));
    }
}

void SigrokAcquisition::Impl::onPacket(const sr_datafeed_packet* p) {
    if (stop_requested) {
        // Once: stopping runs the driver's own end, whose packets come back here.
        if (!stop_sent.exchange(true)) sr_session_stop(session);
        return;
    }
    if (p->type != SR_DF_LOGIC) return;
    const auto* logic = static_cast<const sr_datafeed_logic*>(p->payload);
    if (logic->unitsize == 0 || logic->unitsize > 8) return;
    const std::size_t n = logic->length / logic->unitsize;
    if (playback) {
        if (delivered == 0) t0 = std::chrono::steady_clock::now();
        delivered += n;
    }
    if (!(*on_logic)(static_cast<const std::uint8_t*>(logic->data), n, logic->unitsize)) {
        stop_requested = true;
        if (!stop_sent.exchange(true)) sr_session_stop(session);
        return;
    }
    if (playback) pace();
}

std::string SigrokAcquisition::run(const LogicPacket& on_logic) {
    impl_->on_logic = &on_logic;
    auto feed = [](const sr_dev_inst*, const sr_datafeed_packet* p, void* self) {
        static_cast<Impl*>(self)->onPacket(p);
    };
    sr_session_datafeed_callback_add(impl_->session, feed, impl_.get());
    if (impl_->stop_requested) return {};
    if (sr_session_start(impl_->session) != SR_OK)
        return fmt::format("--device {}: cannot start the acquisition{}", impl_->name(),
                           becauseOf());
    sr_session_run(impl_->session);
    return {};
}

void SigrokAcquisition::stop() {
    impl_->stop_requested = true;
    sr_session_stop(impl_->session);
}

std::vector<std::string> scanSigrokDevices() {
    Context context;
    std::vector<std::string> lines;
    sr_dev_driver** drivers = sr_driver_list(context.ctx);
    for (int i = 0; drivers && drivers[i]; ++i) {
        sr_dev_driver* driver = drivers[i];
        if (sr_driver_init(context.ctx, driver) != SR_OK) continue;
        GSList* found = sr_driver_scan(driver, nullptr);
        for (GSList* l = found; l; l = l->next) {
            auto* sdi = static_cast<sr_dev_inst*>(l->data);
            const char* vendor = sr_dev_inst_vendor_get(sdi);
            const char* model = sr_dev_inst_model_get(sdi);
            const char* conn = sr_dev_inst_connid_get(sdi);
            GSList* channels = sr_dev_inst_channels_get(sdi);
            std::string device = driver->name;
            if (conn && *conn) device += fmt::format(":conn={}", conn);
            std::string what = vendor ? vendor : "";
            if (model && *model) what += (what.empty() ? "" : " ") + std::string(model);
            std::string analog = channelList(channels, SR_CHANNEL_ANALOG);
            lines.push_back(fmt::format("{}\t{}\tlogic: {}{}", device, what,
                                        channelList(channels, SR_CHANNEL_LOGIC),
                                        analog.empty() ? "" : "\tanalog: " + analog));
        }
        g_slist_free(found);
    }
    return lines;
}

}  // namespace busdecode
