#pragma once
// Strings and sequences of the generated C structs (char*, {_maximum, _length, _buffer, _release}),
// with one rule each for who frees what.
//
// Owned (dup_string, set_string, alloc_sequence, assign_sequence): the memory comes from Cyclone's
// allocator and belongs to the message; the generated free function (`X_free(&m,
// DDS_FREE_CONTENTS)`, or the end of an Owned<X>) frees it: strings with dds_free, sequence buffers
// because _release is set. Build owned messages in a fresh (zeroed) message, e.g. an Owned<X>.
//
// Borrowed (borrow_string, borrow_sequence): the message points into C++ storage that must outlive
// it, and must never reach a free function. For large messages whose builder reuses its buffers
// (PointCloud2Builder, LocalMapBuilder).
//
// Reading (to_string, view, to_vector): any message, including a reader's sample.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "runtime/messages.hpp"

namespace ltm::convert {

template <class Seq>
using SequenceElement = std::remove_pointer_t<decltype(Seq::_buffer)>;

// ---- owned -------------------------------------------------------------------------------------

// A copy of `s` from dds_string_alloc: the message it goes into owns it.
char* dup_string(std::string_view s);

// Replaces `field` (freeing what it held with dds_free) with an owned copy of `s`.
void set_string(char*& field, std::string_view s);

// Gives an empty sequence a zeroed buffer of `n` elements from dds_alloc, _release set; returns
// it for filling. Strings inside the elements are set with set_string. Throws std::logic_error on
// a sequence that already holds a buffer (its elements' contents would leak).
template <class Seq>
SequenceElement<Seq>* alloc_sequence(Seq& seq, std::size_t n) {
    if (seq._buffer != nullptr)
        throw std::logic_error("alloc_sequence: the sequence already holds a buffer");
    if (n > UINT32_MAX) throw std::length_error("alloc_sequence: more than 2^32-1 elements");
    seq._length = seq._maximum = static_cast<std::uint32_t>(n);
    seq._release = n > 0;
    seq._buffer =
        n > 0 ? static_cast<SequenceElement<Seq>*>(dds_alloc(n * sizeof(SequenceElement<Seq>)))
              : nullptr;
    return seq._buffer;
}

// An owned copy of `values` into an empty sequence of plain elements (no strings inside).
template <class Seq, class T>
void assign_sequence(Seq& seq, const std::vector<T>& values) {
    static_assert(std::is_same_v<SequenceElement<Seq>, T>, "element types differ");
    static_assert(std::is_trivially_copyable_v<T>, "elements with strings: use alloc_sequence");
    T* out = alloc_sequence(seq, values.size());
    if (!values.empty()) std::memcpy(out, values.data(), values.size() * sizeof(T));
}

// ---- borrowed ----------------------------------------------------------------------------------

// `s`'s own characters: valid while `s` lives unchanged. Never freed through the message.
inline char* borrow_string(std::string& s) { return s.data(); }

// A view of `values` (valid while it lives unchanged), _release clear. The message must not reach
// a free function: the generated one would free strings inside the elements.
template <class Seq, class T>
void borrow_sequence(Seq& seq, const std::vector<T>& values) {
    static_assert(std::is_same_v<SequenceElement<Seq>, T>, "element types differ");
    // The generated struct has no const pointers; the message is only ever read (written out).
    seq._buffer = const_cast<T*>(values.data());
    seq._length = seq._maximum = static_cast<std::uint32_t>(values.size());
    seq._release = false;
}

// ---- reading -----------------------------------------------------------------------------------

// "" for a null string (a zeroed message).
inline std::string to_string(const char* s) { return s ? s : ""; }

template <class T>
struct SequenceView {
    const T* first = nullptr;
    std::uint32_t length = 0;
    const T* begin() const { return first; }
    const T* end() const { return first + length; }
    std::uint32_t size() const { return length; }
    bool empty() const { return length == 0; }
    const T& operator[](std::uint32_t i) const { return first[i]; }
};

// The elements of a sequence, for range-for loops.
template <class Seq>
SequenceView<SequenceElement<Seq>> view(const Seq& seq) {
    return {seq._buffer, seq._buffer ? seq._length : 0u};
}

// A copy of a sequence of plain elements.
template <class Seq>
std::vector<SequenceElement<Seq>> to_vector(const Seq& seq) {
    const auto v = view(seq);
    return {v.begin(), v.end()};
}

}  // namespace ltm::convert
