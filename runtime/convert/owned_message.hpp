#pragma once
// A message that owns its strings and sequence buffers (see dds_string.hpp) and frees them, as
// the generated `X_free(&m, DDS_FREE_CONTENTS)` does, when it goes. Builders return these:
//   publisher.publish(*convert::to_msg(...));
// Moves hand the contents on; copies are not allowed (they would free twice).
#include <utility>

#include "runtime/messages.hpp"

namespace ltm::convert {

template <class T>
class Owned {
  public:
    Owned() = default;
    ~Owned() { free_contents(); }
    Owned(Owned&& other) noexcept : message_(std::exchange(other.message_, T{})) {}
    Owned& operator=(Owned&& other) noexcept {
        if (this != &other) {
            free_contents();
            message_ = std::exchange(other.message_, T{});
        }
        return *this;
    }
    Owned(const Owned&) = delete;
    Owned& operator=(const Owned&) = delete;

    T& operator*() { return message_; }
    const T& operator*() const { return message_; }
    T* operator->() { return &message_; }
    const T* operator->() const { return &message_; }

  private:
    void free_contents() {
        dds_sample_free(&message_, runtime::MessageTraits<T>::descriptor(), DDS_FREE_CONTENTS);
        message_ = T{};
    }

    T message_{};
};

}  // namespace ltm::convert
