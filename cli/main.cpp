#include <cstdio>

#include "globular_version.h"

int main() {
    std::printf("globular %s\n", GLOBULAR_VERSION);
    return 0;
}
