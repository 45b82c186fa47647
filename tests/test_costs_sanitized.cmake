# ctest COST of the slowest tests under the sanitizers (issue 31), included after tests/test_costs.cmake
# in the sanitizer build only (`make test-asan`, CROWDLAB_SANITIZE=ON; see tests/CMakeLists.txt).
#
# Why: the corrector runs about 20 times slower under AddressSanitizer + UBSan at -O1 than in Release,
# so the correction tests, short in Release, are among the longest there, and the Release list would
# start them late. A test not listed here keeps its Release cost from tests/test_costs.cmake.
#
# Seconds in the sanitizer build (2-core machine): the first three are the tests that run the MPFB2
# corridor on its sanitizer-build 3 m corridor: the foot-budget test measured (193 s of wall at load 4,
# 27 Nov 2026), the other two estimated from their 6 m costs (134 and 83 s in session 12) by the share
# of characters they keep (1/2); their own runs were at load 20+ (the joints test: 360 s of wall). The others are measured
# costs from main's build-asan/Testing/Temporary/CTestCostData.txt (session 12). tests/docs checks every name.
set_tests_properties([=[correction:correction: the foot motion budget stops feet jumping in the densest corridor]=] PROPERTIES COST 193)
set_tests_properties([=[correction:correction: joints that touch nobody keep their input, and no joint flips]=] PROPERTIES COST 67)
set_tests_properties([=[correction:correction: planted feet stay at the input's height, so bodies do not float]=] PROPERTIES COST 42)
set_tests_properties([=[correction:correction cli: crowdlab correct IN.glb --out OUT.glb removes the overlap]=] PROPERTIES COST 26)
set_tests_properties([=[correction:correction: dense stationary crowd: overlap -95 %, deviation <= 10 deg, skate <= 1 cm]=] PROPERTIES COST 19)
set_tests_properties([=[correction:correction: moderately dense crowd: overlap removed, shallow residual contacts]=] PROPERTIES COST 11)
set_tests_properties([=[correction:correction: planted feet of a walking corridor crowd stay put (skate <= 1 cm)]=] PROPERTIES COST 10)
set_tests_properties([=[correction:correction: the depenetration pass removes the deep contacts the Newton step leaves]=] PROPERTIES COST 9)
set_tests_properties([=[correction:correction: a looping input gives a looping output with the loop pre-roll]=] PROPERTIES COST 6)
