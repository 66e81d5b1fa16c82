// Waits by condition; the one paced stretch goes through pace_for (time under test).
TEST(Example, WaitsForTheConditionItNeeds) {
    ASSERT_TRUE(testing::wait_until([&] { return done(); }));
    testing::pace_for(std::chrono::milliseconds(20));  // a simulated device's period
    const auto slept_for_note = "sleep_forever is a name, not a call";
}
