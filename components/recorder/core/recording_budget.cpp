#include "recorder/core/recording_budget.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace ltm::recorder {
namespace {

namespace fs = std::filesystem;

struct Found {
    fs::file_time_type mtime;
    std::string path;
    std::uint64_t bytes = 0;
    bool protected_file = false;
};

std::string canonical_or_same(const std::string& path) {
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(path, ec);
    return ec ? path : c.string();
}

std::string mib(std::uint64_t bytes) { return std::to_string((bytes + (1u << 19)) >> 20) + " MiB"; }

}  // namespace

BudgetResult enforce_budget(const std::string& dir, const RecordingBudget& budget,
                            const std::set<std::string>& protect) {
    BudgetResult result;
    std::set<std::string> kept_safe;
    for (const std::string& p : protect) kept_safe.insert(canonical_or_same(p));
    std::vector<Found> files;
    std::error_code ec;
    if (!fs::exists(dir, ec)) return result;
    fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
    for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        std::error_code fec;
        if (!it->is_regular_file(fec) || it->is_symlink(fec)) continue;
        if (it->path().extension() != budget.extension) continue;
        Found f;
        f.path = it->path().string();
        f.bytes = it->file_size(fec);
        if (fec) continue;  // gone meanwhile
        f.mtime = it->last_write_time(fec);
        if (fec) continue;
        f.protected_file = kept_safe.count(canonical_or_same(f.path)) > 0;
        files.push_back(std::move(f));
    }
    if (ec) result.error = dir + ": cannot list the recordings: " + ec.message();
    std::sort(files.begin(), files.end(), [](const Found& a, const Found& b) {
        return a.mtime != b.mtime ? a.mtime < b.mtime : a.path < b.path;
    });
    std::uint64_t total = 0;
    for (const Found& f : files) total += f.bytes;
    std::size_t count = files.size();
    auto over = [&] {
        return (budget.max_total_bytes > 0 && total > budget.max_total_bytes) ||
               (budget.keep_newest > 0 && count > budget.keep_newest);
    };
    for (const Found& f : files) {
        if (!over()) break;
        if (f.protected_file) continue;
        std::error_code rec;
        if (!fs::remove(f.path, rec) || rec) {
            if (result.error.empty())
                result.error = f.path + ": cannot remove: " +
                               (rec ? rec.message() : std::string("already gone"));
            if (!rec) {  // removed by someone else meanwhile: it no longer counts
                total -= f.bytes;
                --count;
            }
            continue;
        }
        result.removed.push_back(f.path);
        result.removed_bytes += f.bytes;
        total -= f.bytes;
        --count;
    }
    result.kept_bytes = total;
    result.kept_files = count;
    result.protected_over_budget = budget.max_total_bytes > 0 && total > budget.max_total_bytes;
    return result;
}

std::string describe(const BudgetResult& r) {
    std::string line = "removed " + std::to_string(r.removed.size()) + " recording" +
                       (r.removed.size() == 1 ? "" : "s") + " (" + mib(r.removed_bytes);
    if (!r.removed.empty()) {
        line += ", oldest first: ";
        for (std::size_t i = 0; i < r.removed.size() && i < 3; ++i)
            line += (i ? ", " : "") + fs::path(r.removed[i]).filename().string();
        if (r.removed.size() > 3) line += ", ...";
    }
    line += "); " + std::to_string(r.kept_files) + " kept, " + mib(r.kept_bytes);
    if (!r.error.empty()) line += "; " + r.error;
    return line;
}

}  // namespace ltm::recorder
