#pragma once
// Scenes parsed from text in tests, and the message of the SceneError a bad one raises.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "errors.h"
#include "reporter.h"
#include "scene.h"

namespace globular {

/// @p text parsed as if read from @p file, with `--set` @p overrides, quietly.
inline Scene parseSceneText(const std::string& text, const std::string& file,
                            const std::vector<std::string>& overrides = {}) {
    NullReporter quiet;
    return parseScene(text, file, overrides, quiet);
}

/// The message of the SceneError that parsing @p text throws; fails the test when it
/// throws none, or another exception.
inline std::string sceneErrorOf(const std::string& text, const std::string& file,
                                const std::vector<std::string>& overrides = {}) {
    try {
        parseSceneText(text, file, overrides);
    } catch (const SceneError& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected a SceneError, got another exception: " << e.what();
        return "";
    }
    ADD_FAILURE() << "expected a SceneError for:\n" << text;
    return "";
}

}  // namespace globular
