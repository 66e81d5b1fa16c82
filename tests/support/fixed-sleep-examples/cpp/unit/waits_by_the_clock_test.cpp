// Waits 300 ms and hopes the daemon is done by then.
TEST(Example, WaitsByTheClock) {
    start();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_TRUE(done());
}
