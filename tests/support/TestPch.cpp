// Holds the precompiled header the console's suites share (tests/CMakeLists.txt).
