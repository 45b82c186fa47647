# ctest COST of the slowest tests under the sanitizers (issue 31), included after tests/test_costs.cmake
# in the sanitizer build only (`make test-asan`, CROWDLAB_SANITIZE=ON; see tests/CMakeLists.txt).
#
# Why: the corrector and the pipeline run many times slower under AddressSanitizer + UBSan than in Release,
# so tests that are short in Release are among the longest there, and the Release list would start them
# late. A test not listed here keeps its Release cost from tests/test_costs.cmake (the browser tests and the demo
# stimuli keep large ones but take under 1 s here, where they skip: started first, they cost nothing.)
#
# Seconds of every test that took 5 s or more in `make test-asan`'s ctest at -Og (578 tests, 646 s of test
# time, 324 s of wall at -j2; main ad2f157 with the -Og flags, the 2-core Intel Xeon VM with nothing else
# running, 29 Nov 2026 05:30 UTC; build-asan/Testing/Temporary/CTestCostData.txt), rounded. tests/docs
# checks every name.
set_tests_properties([=[correction:correction: the foot motion budget stops feet jumping in the densest corridor]=] PROPERTIES COST 47)
set_tests_properties([=[pipeline:run: killed at several stages and resumed, the outputs equal an uninterrupted run's]=] PROPERTIES COST 39)
set_tests_properties([=[pipeline:stage redo: the stimuli's look redoes the clips and the contact sheets, the encoding the clips]=] PROPERTIES COST 26)
set_tests_properties([=[pipeline:run: a deleted crowd file is recomputed and everything downstream equals an uninterrupted run]=] PROPERTIES COST 25)
set_tests_properties([=[correction:loop closure laps: a closure that leaves a character open records the next lap too]=] PROPERTIES COST 24)
set_tests_properties([=[study:participant test: the real window under Xvfb, driven by xdotool, killed and resumed]=] PROPERTIES COST 23)
set_tests_properties([=[analysis:analyze report: every simulated study gets a report with finite or 'Not fitted' cells]=] PROPERTIES COST 21)
set_tests_properties([=[crowd:orca obstacles: half-planes exclude every colliding velocity, admit passing the end]=] PROPERTIES COST 19)
set_tests_properties([=[correction:correction cli: crowdlab correct IN.glb --out OUT.glb removes the overlap]=] PROPERTIES COST 18)
set_tests_properties([=[body:200 sampled MPFB2 shapes: half of each sex, per-sex height distributions, varied looks]=] PROPERTIES COST 17)
set_tests_properties([=[correction:loop closure laps: the progress counts the extra lap and ends at its total]=] PROPERTIES COST 16)
set_tests_properties([=[pipeline:stage redo: a crowd, animation or correction change redoes its stage and exactly its dependants]=] PROPERTIES COST 16)
set_tests_properties([=[fuzz:mutated BVH clips through the importer and retargeting end in success or InputError]=] PROPERTIES COST 15)
set_tests_properties([=[correction:correction: joints that touch nobody keep their input, and no joint flips]=] PROPERTIES COST 14)
set_tests_properties([=[correction:correction: dense stationary crowd: overlap -95 %, deviation <= 10 deg, skate <= 1 cm]=] PROPERTIES COST 14)
set_tests_properties([=[pipeline:run with the default MPFB2 assets: crowd files carry the shaped meshes, real sex and height]=] PROPERTIES COST 13)
set_tests_properties([=[correction:correction: planted feet stay at the input's height, so bodies do not float]=] PROPERTIES COST 12)
set_tests_properties([=[stimuli:levels of detail hold the face to half their error bound]=] PROPERTIES COST 11)
set_tests_properties([=[pipeline:run on a full disk: exit 1, the file and the OS's reason named, no temporary left]=] PROPERTIES COST 11)
set_tests_properties([=[pipeline:ours loops without a seam, keeps its planted feet and flips no joint]=] PROPERTIES COST 10)
set_tests_properties([=[correction:correction: the depenetration pass removes the deep contacts the Newton step leaves]=] PROPERTIES COST 10)
set_tests_properties([=[correction:correction: planted feet of a walking corridor crowd stay put (skate <= 1 cm)]=] PROPERTIES COST 8)
set_tests_properties([=[correction:correction: moderately dense crowd: overlap removed, shallow residual contacts]=] PROPERTIES COST 8)
set_tests_properties([=[pipeline:baseline and ours of a condition are rendered with the identical camera]=] PROPERTIES COST 7)
set_tests_properties([=[fuzz:mutated crowd GLBs through correct, metrics, export-csv and the motion importer]=] PROPERTIES COST 7)
set_tests_properties([=[body:outfits are drawn per body from their own stream: the shapes are the same dressed or not]=] PROPERTIES COST 7)
set_tests_properties([=[pipeline:render on a full disk: exit 1, the file and the OS's reason named, no broken clip or frame left]=] PROPERTIES COST 6)
set_tests_properties([=[stimuli:mannequin mesh: the narrow band gives the mesh of every capsule at every point, bit for bit]=] PROPERTIES COST 6)
set_tests_properties([=[body:skin, trousers and shoes stay behind the garments that cover them, for every outfit]=] PROPERTIES COST 5)
set_tests_properties([=[fuzz:mutated specs through validate end in exit 0 or 2 with a message]=] PROPERTIES COST 5)
set_tests_properties([=[correction:correction: a looping input gives a looping output with the loop pre-roll]=] PROPERTIES COST 5)
set_tests_properties([=[pipeline:run --strict and check-stimuli judge every clip by the spec's render.check]=] PROPERTIES COST 5)
set_tests_properties([=[correction:follow root offsets: the dense corridor corrected twice follows its pushed roots with fewer flips and less float, in twice the steps]=] PROPERTIES COST 44)
