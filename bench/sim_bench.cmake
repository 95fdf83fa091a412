# Benchmarks of globular_sim.
add_executable(sim_bench sim_bench.cpp)
target_link_libraries(sim_bench PRIVATE globular_sim benchmark::benchmark)
