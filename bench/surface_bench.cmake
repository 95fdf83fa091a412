# Benchmarks of globular_surface (not part of ctest; the 1e6 cases are run by hand).
add_executable(surface_bench surface_bench.cpp)
target_link_libraries(surface_bench PRIVATE globular_allocator globular_surface OpenVDB::openvdb
                      benchmark::benchmark)
# Helper of surface_vs_vdb_tool.sh: the same particles for vdb_tool, and our timings.
add_executable(globular_surface_compare surface_compare.cpp)
target_link_libraries(globular_surface_compare PRIVATE globular_allocator globular_surface OpenVDB::openvdb)
