// Owned strings and sequences are freed by the generated free functions (no leak, no double free:
// run under valgrind or ASan to see it); borrowed ones are left alone; reading tolerates nulls.
#include "runtime/convert/dds_string.hpp"

#include <gtest/gtest.h>

#include "runtime/convert/owned_message.hpp"

using namespace ltm;
using namespace ltm::convert;

TEST(DdsString, DupCopiesAndTheGeneratedFreeReleasesIt) {
    msg::Status s{};
    std::string text = "bad_cloud";
    s.key = dup_string(text);
    text[0] = 'X';  // the copy is independent
    EXPECT_STREQ(s.key, "bad_cloud");
    s.message = dup_string("");
    EXPECT_STREQ(s.message, "");
    // Frees both (valgrind: no leak); Cyclone 0.10 leaves the string pointers dangling, which is
    // why Owned<T> zeroes the message after freeing it.
    ltm_msgs_msg_dds__Status__free(&s, DDS_FREE_CONTENTS);
}

TEST(DdsString, SetStringReplacesAndFreesTheOldOne) {
    msg::Status s{};
    set_string(s.component, "odometry");
    set_string(s.component, std::string(300, 'a'));
    set_string(s.component, s.component);  // from its own characters
    EXPECT_EQ(std::string(s.component), std::string(300, 'a'));
    std::string with_nul("ab\0cd", 5);
    set_string(s.key, with_nul);  // a C string ends at its first NUL
    EXPECT_STREQ(s.key, "ab");
    ltm_msgs_msg_dds__Status__free(&s, DDS_FREE_CONTENTS);
}

TEST(DdsString, ToStringOfNullIsEmpty) {
    EXPECT_EQ(to_string(nullptr), "");
    EXPECT_EQ(to_string("map"), "map");
}

TEST(DdsSequence, AllocatedElementsWithStringsAreFreedByTheGeneratedFree) {
    msg::Path p{};
    set_string(p.header.frame_id, "map");
    msg::PoseStamped* poses = alloc_sequence(p.poses, 3);
    ASSERT_NE(poses, nullptr);
    EXPECT_EQ(p.poses._length, 3u);
    EXPECT_EQ(p.poses._maximum, 3u);
    EXPECT_TRUE(p.poses._release);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(poses[i].header.frame_id, nullptr);  // zeroed
        set_string(poses[i].header.frame_id, "map");
        poses[i].pose.position.x = i;
    }
    double x = 0;
    for (const msg::PoseStamped& ps : view(p.poses)) x += ps.pose.position.x;
    EXPECT_EQ(x, 3.0);
    nav_msgs_msg_dds__Path__free(&p, DDS_FREE_CONTENTS);
    EXPECT_EQ(p.poses._buffer, nullptr);
    EXPECT_EQ(p.poses._length, 0u);
}

TEST(DdsSequence, EmptySequenceAllocatesNothing) {
    msg::Mesh m{};
    EXPECT_EQ(alloc_sequence(m.vertices, 0), nullptr);
    EXPECT_FALSE(m.vertices._release);
    EXPECT_TRUE(view(m.vertices).empty());
    EXPECT_TRUE(to_vector(m.vertices).empty());
    ltm_msgs_msg_dds__Mesh__free(&m, DDS_FREE_CONTENTS);
}

TEST(DdsSequence, AssignCopiesPlainElements) {
    msg::Mesh m{};
    std::vector<float> vertices = {1, 2, 3, 4, 5, 6};
    assign_sequence(m.vertices, vertices);
    vertices[0] = 99;
    EXPECT_EQ(to_vector(m.vertices), (std::vector<float>{1, 2, 3, 4, 5, 6}));
    EXPECT_EQ(view(m.vertices)[5], 6.f);
    EXPECT_EQ(view(m.vertices).size(), 6u);
    ltm_msgs_msg_dds__Mesh__free(&m, DDS_FREE_CONTENTS);
    EXPECT_EQ(m.vertices._buffer, nullptr);
}

TEST(DdsSequence, AllocatingOverAHeldBufferIsRefused) {
    Owned<msg::Mesh> m;
    assign_sequence(m->triangles, std::vector<std::uint32_t>{0, 1, 2});
    EXPECT_THROW(alloc_sequence(m->triangles, 6), std::logic_error);
    EXPECT_EQ(m->triangles._length, 3u);  // unchanged, freed once by Owned
}

TEST(DdsSequence, BorrowedBufferIsLeftToItsOwner) {
    std::vector<float> vertices = {1, 2, 3};
    msg::Mesh m{};
    borrow_sequence(m.vertices, vertices);
    EXPECT_EQ(m.vertices._buffer, vertices.data());
    EXPECT_FALSE(m.vertices._release);
    EXPECT_EQ(to_vector(m.vertices), vertices);
    // The generated free skips a buffer without _release: the vector still owns it.
    ltm_msgs_msg_dds__Mesh__free(&m, DDS_FREE_CONTENTS);
    EXPECT_EQ(vertices[2], 3.f);
}

TEST(DdsString, BorrowedStringIsTheStringsOwnCharacters) {
    std::string frame = "lidar";
    char* p = borrow_string(frame);
    EXPECT_EQ(p, frame.data());
    EXPECT_STREQ(p, "lidar");
}

TEST(OwnedMessage, MovesHandTheContentsOnAndFreeOnce) {
    Owned<msg::Status> a;
    set_string(a->message, "hello");
    Owned<msg::Status> b = std::move(a);
    EXPECT_EQ(a->message, nullptr);  // NOLINT(bugprone-use-after-move): moved-from is empty
    EXPECT_STREQ(b->message, "hello");
    Owned<msg::Status> c;
    set_string(c->message, "replaced");
    c = std::move(b);  // frees "replaced"
    EXPECT_STREQ(c->message, "hello");
    Owned<msg::Status>& same = c;
    c = std::move(same);  // moving onto itself keeps the contents
    EXPECT_STREQ(c->message, "hello");
}
