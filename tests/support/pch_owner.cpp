// Empty on purpose: the object library crowdlab_test_pch exists to compile the test executables' shared
// precompiled header (tests/CMakeLists.txt says why), and CMake needs one source file to attach it to.
