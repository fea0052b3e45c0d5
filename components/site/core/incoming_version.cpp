#include "site/core/incoming_version.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/site_check.hpp"

namespace ltm::site_sync {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kRecord = 24;

void put64(std::uint8_t* p, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) p[i] = std::uint8_t(v >> (8 * i));
}
std::uint64_t get64(const std::uint8_t* p) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= std::uint64_t(p[i]) << (8 * i);
    return v;
}

std::string record(ChunkRef c, std::uint64_t hash) {
    std::uint8_t r[kRecord];
    put64(r, std::uint64_t(c.file) | (std::uint64_t(c.chunk) << 32));
    put64(r + 8, hash);
    put64(r + 16, chunk_hash(r, 16));
    return std::string(reinterpret_cast<const char*>(r), kRecord);
}

void sync_file(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw common::IoError(path, std::strerror(errno));
    const int r = ::fsync(fd);
    ::close(fd);
    if (r != 0) throw common::IoError(path, "fsync failed");
}

}  // namespace

IncomingVersion::IncomingVersion(std::string dir, const VersionOffer& offer, TransferPlan plan)
    : dir_(std::move(dir)), offer_(offer), plan_(std::move(plan)) {
    std::error_code ec;
    const std::string text = write_offer(offer_);
    const std::string offer_file = dir_ + "/offer.txt";
    bool same = false;
    if (fs::exists(offer_file, ec)) {
        try {
            same = common::read_file(offer_file, "offer.txt") == text;
        } catch (const common::IoError&) {
        }
    }
    if (!same) fs::remove_all(dir_, ec);
    fs::remove_all(version_dir(), ec);  // an assembly cut short: made again
    fs::create_directories(dir_ + "/parts", ec);
    if (ec) throw common::IoError(dir_, "cannot create: " + ec.message());
    if (!same) common::write_file_atomic(offer_file, text);
    have_.resize(offer_.files.size());
    for (std::size_t i = 0; i < offer_.files.size(); ++i)
        if (plan_.sends(i)) {
            have_[i].assign(offer_.chunks(i), false);
            missing_count_ += have_[i].size();
        }
    resume();
}

IncomingVersion::~IncomingVersion() {
    for (const auto& [file, fd] : fds_) ::close(fd);
    if (journal_fd_ >= 0) ::close(journal_fd_);
}

std::string IncomingVersion::part_path(std::uint32_t file) const {
    return dir_ + "/parts/f" + std::to_string(file);
}

int IncomingVersion::part_fd(std::uint32_t file) {
    const auto it = fds_.find(file);
    if (it != fds_.end()) return it->second;
    const std::string path = part_path(file);
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw common::IoError(path, std::string("cannot open: ") + std::strerror(errno));
    fds_[file] = fd;
    return fd;
}

// Chunks recorded by an earlier start, kept when their bytes still hash right.
void IncomingVersion::resume() {
    std::string journal;
    try {
        journal = common::read_file(dir_ + "/received", "received");
    } catch (const common::IoError&) {
    }
    for (std::size_t at = 0; at + kRecord <= journal.size(); at += kRecord) {
        const auto* r = reinterpret_cast<const std::uint8_t*>(journal.data() + at);
        if (get64(r + 16) != chunk_hash(r, 16)) break;  // torn: the rest is not trusted
        const std::uint64_t key = get64(r);
        const ChunkRef c{std::uint32_t(key), std::uint32_t(key >> 32)};
        const std::uint64_t hash = get64(r + 8);
        if (!offer_.valid(c) || have_[c.file].empty() || have_[c.file][c.chunk]) continue;
        std::string bytes(offer_.chunk_length(c), '\0');
        const ssize_t got =
            ::pread(part_fd(c.file), bytes.data(), bytes.size(), off_t(offer_.chunk_offset(c)));
        if (got != ssize_t(bytes.size()) || chunk_hash(bytes.data(), bytes.size()) != hash)
            continue;
        have_[c.file][c.chunk] = true;
        stored_[c.file][c.chunk] = hash;
        --missing_count_;
        ++resumed_;
    }
    rewrite_journal();
}

void IncomingVersion::rewrite_journal() {
    if (journal_fd_ >= 0) ::close(journal_fd_);
    journal_fd_ = -1;
    std::string text;
    for (const auto& [file, chunks] : stored_)
        for (const auto& [chunk, hash] : chunks) text += record({file, chunk}, hash);
    const std::string path = dir_ + "/received";
    common::write_file_atomic(path, text);
    journal_fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
    if (journal_fd_ < 0) throw common::IoError(path, std::strerror(errno));
}

void IncomingVersion::append_record(ChunkRef c, std::uint64_t hash) {
    const std::string r = record(c, hash);
    if (::write(journal_fd_, r.data(), r.size()) != ssize_t(r.size()))
        throw common::IoError(dir_ + "/received", std::string("write: ") + std::strerror(errno));
}

ChunkVerdict IncomingVersion::accept(ChunkRef c, std::uint64_t hash, const void* data,
                                     std::size_t size) {
    if (!offer_.valid(c) || have_[c.file].empty()) return ChunkVerdict::kNotAsked;
    if (have_[c.file][c.chunk]) return ChunkVerdict::kDuplicate;
    if (size != offer_.chunk_length(c) || chunk_hash(data, size) != hash)
        return ChunkVerdict::kDamaged;
    const int fd = part_fd(c.file);
    if (::pwrite(fd, data, size, off_t(offer_.chunk_offset(c))) != ssize_t(size))
        throw common::IoError(part_path(c.file), std::string("write: ") + std::strerror(errno));
    append_record(c, hash);
    have_[c.file][c.chunk] = true;
    stored_[c.file][c.chunk] = hash;
    --missing_count_;
    bytes_stored_ += size;
    return ChunkVerdict::kStored;
}

bool IncomingVersion::has(ChunkRef c) const {
    return offer_.valid(c) && !have_[c.file].empty() && have_[c.file][c.chunk];
}

std::vector<ChunkRef> IncomingVersion::missing(std::size_t at_most) const {
    std::vector<ChunkRef> out;
    for (std::uint32_t f = 0; f < have_.size() && out.size() < at_most; ++f)
        for (std::uint32_t c = 0; c < have_[f].size() && out.size() < at_most; ++c)
            if (!have_[f][c]) out.push_back({f, c});
    return out;
}

void IncomingVersion::forget_file(std::uint32_t file) {
    if (have_[file].empty()) {  // held by the robot, but its copy is not the offer's: sent
        plan_.local_source[file].clear();
        have_[file].assign(offer_.chunks(file), false);
        missing_count_ += have_[file].size();
        return;
    }
    for (std::size_t c = 0; c < have_[file].size(); ++c)
        if (have_[file][c]) {
            have_[file][c] = false;
            ++missing_count_;
        }
    stored_.erase(file);
    const auto it = fds_.find(file);
    if (it != fds_.end()) {
        ::close(it->second);
        fds_.erase(it);
    }
    std::error_code ec;
    fs::remove(part_path(file), ec);
}

std::string IncomingVersion::assemble() {
    if (missing_count_ > 0) return std::to_string(missing_count_) + " chunks still missing";
    std::error_code ec;
    fs::remove_all(version_dir(), ec);
    std::vector<std::uint32_t> wrong;
    std::string problem;
    for (std::uint32_t i = 0; i < offer_.files.size(); ++i) {
        const VersionFile& f = offer_.files[i];
        const fs::path target = fs::path(version_dir()) / f.path;
        fs::create_directories(target.parent_path(), ec);
        const std::string from = plan_.sends(i) ? part_path(i) : plan_.local_source[i];
        if (plan_.sends(i)) {
            if (::ftruncate(part_fd(i), off_t(f.size)) != 0)  // an empty file has no bytes
                throw common::IoError(part_path(i), "cannot size");
            sync_file(from);
        }
        std::uint64_t size = 0, hash = 0;
        try {
            hash = hash_file(from, &size);
        } catch (const common::IoError&) {
            size = ~0ull;
        }
        if (size != f.size || hash != f.hash) {
            wrong.push_back(i);
            if (problem.empty())
                problem = f.path + ": " + (plan_.sends(i) ? "received" : "held") +
                          " bytes do not have the offer's size and hash";
            continue;
        }
        fs::create_hard_link(from, target, ec);
        if (ec) fs::copy_file(from, target, fs::copy_options::overwrite_existing, ec);
        if (ec) throw common::IoError(target.string(), "cannot place: " + ec.message());
    }
    if (wrong.empty()) {
        problem = map::check_map_dir(version_dir() + "/map");
        if (problem.empty())
            problem =
                map::check_maintained_map_file(version_dir() + "/maintenance/long_term_map.bin");
        if (problem.empty()) return "";
    }
    for (const std::uint32_t i : wrong) forget_file(i);
    if (!wrong.empty()) rewrite_journal();
    fs::remove_all(version_dir(), ec);
    return problem;
}

}  // namespace ltm::site_sync
