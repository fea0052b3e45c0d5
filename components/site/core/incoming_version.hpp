#pragma once
// A version on its way to the robot (site_sync, issue 26), kept on the robot's disk so that an
// interrupted transfer goes on where it stopped after a restart of either side:
//   SITE/incoming/<offer id>/offer.txt      the offer (version_files.hpp)
//   SITE/incoming/<offer id>/parts/f<i>     file i of the offer as its chunks arrive (sparse)
//   SITE/incoming/<offer id>/received       one 24-byte record a stored chunk: file, chunk, the
//                                           chunk's hash, a hash of those (a torn record ends it)
//   SITE/incoming/<offer id>/version/       the version assembled once every chunk is there
// A chunk is stored only when its length and hash are the offer's; on a resume every recorded
// chunk is read back and kept only when its bytes still hash right (the record is appended after
// the bytes, without fsync: a power loss costs chunks, never a wrong one). Assembly checks every
// file of the version against the offer's size and hash (files the robot held included) and the
// version's own check (the map's manifest and files, the maintained map's sections); a file that
// fails loses its chunks and is asked for again. Nothing here touches the site's versions:
// map::SiteStore::adopt commits the assembled folder.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "site/core/transfer_plan.hpp"
#include "site/core/version_files.hpp"

namespace ltm::site_sync {

enum class ChunkVerdict {
    kStored,     // new, checked, on disk
    kDuplicate,  // held already
    kNotAsked,   // not a chunk of a file this transfer sends
    kDamaged,    // its length or hash is not the offer's: refused
};

class IncomingVersion {
  public:
    // Opens or resumes the transfer of `offer` in `dir` (created). A folder holding another
    // offer is started afresh. Throws common::IoError when the folder cannot be written.
    IncomingVersion(std::string dir, const VersionOffer& offer, TransferPlan plan);
    ~IncomingVersion();
    IncomingVersion(const IncomingVersion&) = delete;
    IncomingVersion& operator=(const IncomingVersion&) = delete;

    ChunkVerdict accept(ChunkRef c, std::uint64_t hash, const void* data, std::size_t size);
    bool has(ChunkRef c) const;
    // The chunks still missing, in order, at most `at_most`.
    std::vector<ChunkRef> missing(std::size_t at_most) const;
    std::size_t missing_count() const { return missing_count_; }
    std::size_t resumed_chunks() const { return resumed_; }       // kept from an earlier start
    std::uint64_t bytes_stored() const { return bytes_stored_; }  // by this object

    // Every chunk there: builds version_dir() and checks it. "" when the version is whole; else
    // one line, and the files that failed are asked for again (missing_count() > 0).
    std::string assemble();
    std::string version_dir() const { return dir_ + "/version"; }
    const std::string& dir() const { return dir_; }
    const VersionOffer& offer() const { return offer_; }
    const TransferPlan& plan() const { return plan_; }

  private:
    std::string part_path(std::uint32_t file) const;
    int part_fd(std::uint32_t file);
    void resume();
    void rewrite_journal();
    void append_record(ChunkRef c, std::uint64_t hash);
    void forget_file(std::uint32_t file);  // its chunks asked for again

    std::string dir_;
    VersionOffer offer_;
    TransferPlan plan_;
    std::vector<std::vector<bool>> have_;  // per file (empty: held, not sent)
    std::map<std::uint32_t, std::map<std::uint32_t, std::uint64_t>> stored_;  // file -> chunk
    std::map<std::uint32_t, int> fds_;
    int journal_fd_ = -1;
    std::size_t missing_count_ = 0, resumed_ = 0;
    std::uint64_t bytes_stored_ = 0;
};

}  // namespace ltm::site_sync
