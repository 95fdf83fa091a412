# Benchmarks of globular_sim.
add_executable(sim_bench sim_bench.cpp)
target_link_libraries(sim_bench PRIVATE globular_allocator globular_sim benchmark::benchmark)
target_compile_definitions(sim_bench PRIVATE GLOBULAR_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# Peer comparisons (bench/lammps/compare.sh) and bench/run.sh: the workload as files, and
# a fixed number of steps on it timed at given thread counts.
add_executable(make_workload make_workload.cpp)
target_link_libraries(make_workload PRIVATE globular_allocator globular_sim)
add_executable(sim_steps sim_steps.cpp)
target_link_libraries(sim_steps PRIVATE globular_allocator globular_sim)

# docs/scale.md: the halo of a domain decomposition of a cached frame.
add_executable(halo_fraction halo_fraction.cpp)
target_link_libraries(halo_fraction PRIVATE globular_allocator globular_sim)

# Mesh colliders: MeshSdf::sample per globule over the bowl of scenes/effectors.
add_executable(mesh_collider_bench mesh_collider_bench.cpp)
target_link_libraries(mesh_collider_bench PRIVATE globular_allocator globular_sim benchmark::benchmark)
target_compile_definitions(mesh_collider_bench PRIVATE GLOBULAR_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

# The per-frame statistics' share of a frame (issue 18).
add_executable(frame_stats_bench frame_stats_bench.cpp)
target_link_libraries(frame_stats_bench PRIVATE globular_allocator globular_sim)
