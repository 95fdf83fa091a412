#pragma once
// A Reporter for tests: records every message and progress step. When given a stage
// name, it also checks that every progress report comes from that stage.

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "reporter.h"

namespace globular {

class RecordingReporter final : public Reporter {
public:
    explicit RecordingReporter(std::string expectedStage = "")
        : mExpectedStage(std::move(expectedStage)) {}

    void info(std::string_view m) override { infos.emplace_back(m); }
    void warn(std::string_view m) override { warnings.emplace_back(m); }
    void progress(std::string_view stage, long done, long total) override {
        if (!mExpectedStage.empty()) {
            EXPECT_EQ(stage, mExpectedStage);
        }
        steps.emplace_back(done, total);
    }

    std::vector<std::string> infos, warnings;
    std::vector<std::pair<long, long>> steps;

private:
    std::string mExpectedStage;
};

}  // namespace globular
