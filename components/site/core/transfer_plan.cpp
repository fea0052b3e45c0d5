#include "site/core/transfer_plan.hpp"

namespace ltm::site_sync {

TransferPlan plan_transfer(const VersionOffer& offer, const HeldFiles& held) {
    TransferPlan plan;
    plan.local_source.resize(offer.files.size());
    for (std::size_t i = 0; i < offer.files.size(); ++i) {
        const VersionFile& f = offer.files[i];
        plan.bytes_total += f.size;
        if (const std::string* own = held.find(f.size, f.hash)) {
            plan.local_source[i] = *own;
            continue;
        }
        ++plan.files_to_send;
        plan.bytes_to_send += f.size;
        for (std::uint32_t c = 0; c < offer.chunks(i); ++c)
            plan.chunks.push_back({std::uint32_t(i), c});
    }
    return plan;
}

}  // namespace ltm::site_sync
