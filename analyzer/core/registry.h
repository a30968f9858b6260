#pragma once
// All decoders known to this process: built-ins and out-of-tree plugins register their
// factories here (the plugin loader does it for every plugin it finds).
#include <memory>
#include <string>
#include <vector>

#include "decoder.h"

namespace busdecode {

class Registry {
public:
    static Registry& instance();
    // Takes shared ownership; a second factory with the same id is ignored (first wins).
    void add(std::shared_ptr<const DecoderFactory> f);
    const DecoderFactory* find(const std::string& id) const;
    std::vector<const DecoderFactory*> all() const;  // sorted by id
    // Creates a decoder from user option texts (validated; throws InputError).
    std::unique_ptr<Decoder> create(const std::string& id,
                                    const std::map<std::string, std::string>& options) const;

private:
    std::vector<std::shared_ptr<const DecoderFactory>> factories_;
};

// Template factory for decoders whose constructor takes (const Options&).
template <class D>
class SimpleFactory : public DecoderFactory {
public:
    explicit SimpleFactory(DecoderInfo info) : info_(std::move(info)) {}
    const DecoderInfo& info() const override { return info_; }
    std::unique_ptr<Decoder> create(const Options& o) const override {
        return std::make_unique<D>(o);
    }

private:
    DecoderInfo info_;
};

// The factory of a decoder stacked on others whose code is linked into it
// (core/stacked.h: TMCL on UART, the TMC8100 on SPI): it registers theirs before it
// creates the decoder, so that the registry knows them even when their own plugins were
// not loaded (app/plugin_loader.h loads only the plugins a run asks for). The registry
// keeps the first of equal ids: a lower decoder's own plugin, if loaded first, wins.
template <class D>
class StackedFactory : public SimpleFactory<D> {
public:
    StackedFactory(DecoderInfo info, std::vector<std::shared_ptr<const DecoderFactory>> lower)
        : SimpleFactory<D>(std::move(info)), lower_(std::move(lower)) {}
    std::unique_ptr<Decoder> create(const Options& o) const override {
        for (const auto& f : lower_)
            Registry::instance().add(f);
        return SimpleFactory<D>::create(o);
    }

private:
    std::vector<std::shared_ptr<const DecoderFactory>> lower_;
};

}  // namespace busdecode
