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

}  // namespace busdecode
