#include "plugin_loader.h"

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonObject>
#include <QPluginLoader>
#include <QString>

#include "busdecode/plugin.h"
#include "core/options.h"
#include "core/registry.h"

namespace busdecode {

namespace {

struct PluginFile {
    QString path;
    // The decoder ids its metadata lists (plugins/plugin_template.cpp.in); `listed` false
    // when it lists none, and so must be loaded to be known.
    std::vector<std::string> ids;
    bool listed = false;
    bool loaded = false;
};

QStringList pluginDirs() {
    QStringList dirs;
    const QString app =
        QCoreApplication::instance() ? QCoreApplication::applicationDirPath() : QString();
    if (const char* env = std::getenv("BUSDECODE_PLUGIN_PATH"))
        for (const auto& d : QString::fromLocal8Bit(env).split(':', Qt::SkipEmptyParts))
            dirs << d;
    if (!app.isEmpty()) {
        dirs << app + "/plugins";
        dirs << app + "/../lib/busdecode/plugins";
        dirs << app + "/../lib/x86_64-linux-gnu/busdecode/plugins";
    }
    return dirs;
}

// Every decoder is a plugin, so without one `decode` can do nothing: say where it looked.
std::string noPluginsFound(const QStringList& dirs) {
    std::vector<std::string> shown;
    for (const auto& d : dirs)
        shown.push_back(QDir::cleanPath(d).toStdString());
    return fmt::format(
        "no decoder plugins (busdecode_*.so) found; searched: {}; set BUSDECODE_PLUGIN_PATH "
        "to the directory holding them (several: separated by ':')",
        fmt::join(shown, ", "));
}

std::vector<PluginFile> findPluginFiles(const QStringList& dirs) {
    std::vector<PluginFile> files;
    std::set<QString> seen;
    for (const auto& d : dirs) {
        QDir dir(d);
        if (!dir.exists()) continue;
        for (const auto& file : dir.entryList({"*.so"}, QDir::Files, QDir::Name)) {
            PluginFile f;
            f.path = dir.absoluteFilePath(file);
            if (!seen.insert(QFileInfo(f.path).canonicalFilePath()).second) continue;
            // Qt reads the metadata from the file without loading it.
            const QJsonObject meta = QPluginLoader(f.path).metaData();
            if (meta.value("IID").toString() == QLatin1String(BUSDECODE_PLUGIN_IID)) {
                const QJsonArray ids =
                    meta.value("MetaData").toObject().value("decoders").toArray();
                for (const auto& id : ids)
                    if (id.isString()) f.ids.push_back(id.toString().toStdString());
                f.listed = !f.ids.empty();
            }
            files.push_back(std::move(f));
        }
    }
    return files;
}

void load(PluginFile& file) {
    file.loaded = true;
    QPluginLoader loader(file.path);
    QObject* root = loader.instance();
    auto* plugin = root ? qobject_cast<DecoderPlugin*>(root) : nullptr;
    if (!plugin) {
        // A Qt plugin that loads but is not ours: most likely a decoder built against
        // another version of the interface (plugin.h).
        const std::string why = root ? fmt::format(
                                           "it does not implement {}: rebuild it against "
                                           "this version's busdecode/plugin.h",
                                           BUSDECODE_PLUGIN_IID)
                                     : loader.errorString().toStdString();
        fmt::print(stderr, "decode: warning: {}: not a busdecode plugin ({})\n",
                   file.path.toStdString(), why);
        return;
    }
    for (auto& f : plugin->factories())
        Registry::instance().add(f);
}

}  // namespace

void loadPlugins(const std::vector<std::string>& wanted) {
    static std::mutex m;
    static std::vector<PluginFile> files;
    static bool found = false;
    std::lock_guard<std::mutex> lock(m);
    static QStringList dirs;  // kept for the error when there is no plugin
    if (!found) {
        dirs = pluginDirs();
        files = findPluginFiles(dirs);
        found = true;
    }
    if (files.empty() && Registry::instance().all().empty()) throw InputError(noPluginsFound(dirs));
    const auto isWanted = [&](const PluginFile& f) {
        if (wanted.empty() || !f.listed) return true;
        return std::any_of(f.ids.begin(), f.ids.end(), [&](const std::string& id) {
            return std::find(wanted.begin(), wanted.end(), id) != wanted.end();
        });
    };
    for (auto& f : files)
        if (!f.loaded && isWanted(f)) load(f);
}

}  // namespace busdecode
