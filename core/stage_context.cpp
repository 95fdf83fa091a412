#include "stage_context.h"

#include "atomic_file.h"

namespace globular {

void StageContext::sweepTemporaries(const std::string& stage) const {
    if (const std::size_t stale = removeStaleTemporaries(outDir)) {
        report().info(stage + ": removed " + std::to_string(stale) +
                      " temporary files left by an interrupted run");
    }
}

}  // namespace globular
