#pragma once
// A typed writer. publish() never throws: it returns false when the sample was not delivered
// (stop requested while blocked on back-pressure, or a DDS error, which is logged).
#include <dds/dds.h>

#include <atomic>
#include <memory>
#include <string>

#include "runtime/logging.hpp"
#include "runtime/qos.hpp"

struct ddsi_sertype;

namespace ltm::runtime {

struct WriterHandle {
    dds_entity_t writer = 0;
    std::string topic;  // absolute ROS name
    QosProfile profile;
    const std::atomic<bool>* stop = nullptr;
    Logger log{""};
    std::atomic<std::uint64_t> published{0};
    std::atomic<std::uint64_t> failed{0};
    std::atomic<std::uint64_t> retried{0};        // writes repeated after a back-pressure timeout
    std::atomic<dds_time_t> last_source_time{0};  // strictly increasing per writer
};

// Writes one sample; blocks (in slices of max_blocking_s) on a keep-all topic whose readers are
// full. Each sample gets a source timestamp strictly after the writer's previous one; a write
// retried after a timeout keeps it, so readers recognise a second copy (exactly once).
bool write_sample(WriterHandle& handle, const void* sample);

// A writer of raw CDR bytes (replay).
struct RawWriterHandle : WriterHandle {
    const ::ddsi_sertype* type = nullptr;
};
// Writes serialized CDR; blocks on back-pressure like write_sample.
bool write_raw(RawWriterHandle& handle, const std::uint8_t* cdr, std::size_t size);

template <class T>
class Publisher {
  public:
    Publisher() = default;
    explicit Publisher(std::shared_ptr<WriterHandle> h) : h_(std::move(h)) {}
    bool publish(const T& message) { return h_ && write_sample(*h_, &message); }
    // One attempt, blocking at most the profile's max_blocking_s: DDS_RETCODE_OK, or
    // DDS_RETCODE_TIMEOUT while the writer's history is full of unacknowledged samples (a slow or
    // broken link), or another DDS error. Neither retries nor logs: the caller decides.
    dds_return_t try_publish(const T& message) {
        if (!h_) return DDS_RETCODE_PRECONDITION_NOT_MET;
        const dds_return_t rc = dds_write(h_->writer, &message);
        if (rc == DDS_RETCODE_OK) ++h_->published;
        return rc;
    }
    bool valid() const { return h_ != nullptr; }
    const std::string& topic() const { return h_->topic; }
    // Readers currently matched (in this process or elsewhere).
    std::uint32_t matched() const {
        dds_publication_matched_status_t st{};
        return (h_ && dds_get_publication_matched_status(h_->writer, &st) == DDS_RETCODE_OK)
                   ? st.current_count
                   : 0;
    }
    std::uint64_t published() const { return h_ ? h_->published.load() : 0; }
    // Writes repeated after a back-pressure timeout (each sample still delivered once).
    std::uint64_t retried() const { return h_ ? h_->retried.load() : 0; }

  private:
    std::shared_ptr<WriterHandle> h_;
};

}  // namespace ltm::runtime
