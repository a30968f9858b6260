// Where recycled events go: back to the store that output them, or, filled on the other
// reader thread (EventHome 1), back to that thread's pool as they are, to be emptied
// there when taken (event_pool.h).
#include <gtest/gtest.h>

#include "core/event_pool.h"

using namespace busdecode;

namespace {

EventPtr used(std::uint8_t home, const char* summary) {
    auto e = std::make_unique<Event>();
    e->proto = "bissc";
    e->type = "frame";
    e->start = 7;
    e->add("pos", std::int64_t(42));
    e->error("crc");
    e->summary = summary;
    EventHome::set(*e, home);
    return e;
}

}  // namespace

TEST(RecycledEvents, EventsFromTheOtherThreadGoHomeAsTheyAre) {
    EventPool own, other;
    {
        RecycledEvents store(/*keep=*/4, &own);
        store.sendHome(&other);
        store.recycle(used(1, "from the other thread"));
        store.recycle(used(0, "from this thread"));
        // This thread's event is emptied and kept for its next fresh().
        EventPtr mine = store.fresh();
        EXPECT_TRUE(mine->summary.empty());
        EXPECT_TRUE(mine->fields.empty());
        EXPECT_EQ(EventHome::of(*mine), 0);
    }  // the store gives what it holds for the other thread to that thread's pool
    std::vector<EventPtr> got;
    other.take(got, 10);
    ASSERT_EQ(got.size(), 1u);
    // Not emptied on the way: the thread it goes home to does that.
    EXPECT_EQ(got[0]->summary, "from the other thread");
    EXPECT_EQ(EventHome::of(*got[0]), 1);
    std::vector<EventPtr> none;
    own.take(none, 10);
    EXPECT_TRUE(none.empty());
}

TEST(RecycledEvents, EventsGivenBackAsTheyWereAreEmptiedWhenTaken) {
    EventPool pool;
    std::vector<EventPtr> back;
    for (int i = 0; i < 3; ++i)
        back.push_back(used(1, "last use"));
    pool.give(back);
    RecycledEvents store(/*keep=*/0, &pool);
    for (int i = 0; i < 3; ++i) {
        EventPtr e = store.fresh();
        EXPECT_TRUE(e->proto.empty()) << i;
        EXPECT_TRUE(e->fields.empty()) << i;
        EXPECT_TRUE(e->errors.empty()) << i;
        EXPECT_TRUE(e->summary.empty()) << i;
        EXPECT_EQ(e->start, 0) << i;
        EXPECT_EQ(EventHome::of(*e), 1) << i;  // reset() keeps whose storage it is
    }
}

TEST(RecycledEvents, WithoutAHomePoolEveryEventIsEmptiedAndKept) {
    EventPool own;
    RecycledEvents store(/*keep=*/4, &own);
    store.recycle(used(1, "from the other thread"));
    EventPtr e = store.fresh();
    EXPECT_TRUE(e->summary.empty());
    EXPECT_TRUE(e->fields.empty());
}
