#include "runtime/held_memory.hpp"

namespace ltm::runtime {

void HeldMemory::set(const std::string& part, std::size_t bytes) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (HeldPart& p : parts_) {
        if (p.part == part) {
            p.bytes = bytes;
            return;
        }
    }
    parts_.push_back({part, bytes});
}

std::vector<HeldPart> HeldMemory::parts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return parts_;
}

namespace {

std::string mb(std::size_t bytes) { return std::to_string((bytes + 500'000) / 1'000'000); }

}  // namespace

std::string held_memory_text(
    const std::vector<std::pair<std::string, std::vector<HeldPart>>>& components) {
    std::string text;
    for (const auto& [name, parts] : components) {
        if (parts.empty()) continue;
        std::size_t total = 0;
        for (const HeldPart& p : parts) total += p.bytes;
        text += (text.empty() ? "held: " : ", ") + name + " " + mb(total) + " MB";
        if (parts.size() > 1) {
            text += " (";
            for (std::size_t i = 0; i < parts.size(); ++i)
                text += (i ? ", " : "") + parts[i].part + " " + mb(parts[i].bytes);
            text += ")";
        }
    }
    return text;
}

}  // namespace ltm::runtime
