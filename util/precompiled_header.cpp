// Intentionally empty: the target compiling it builds the precompiled header
// every other target reuses (CMakeLists.txt, lagrange_precompiled_header_owner).
