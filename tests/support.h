// Helpers shared by the tests: where the sample assets are, and skipping when they are absent.
#pragma once

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

namespace ellicast::test {

// ../shared/samples next to the checkout; a user's checkout may not have it.
inline std::filesystem::path shared_samples() { return ELLICAST_SHARED_SAMPLES; }
inline std::filesystem::path source_dir() { return ELLICAST_SOURCE_DIR; }
inline std::filesystem::path binary_dir() { return ELLICAST_BINARY_DIR; }
inline std::filesystem::path ellicast_exe() { return binary_dir() / "ellicast"; }

// True when the shared sample exists; otherwise prints why the test is skipped.
inline bool have_sample(const std::string& relative) {
    if (std::filesystem::exists(shared_samples() / relative)) return true;
    MESSAGE("skipped: " << (shared_samples() / relative).string()
                        << " is absent (the tests read real assets from ../shared/samples)");
    return false;
}

// A fresh empty scratch directory for one test.
inline std::filesystem::path scratch_dir(const std::string& name) {
    auto dir = binary_dir() / "test-scratch" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace ellicast::test
