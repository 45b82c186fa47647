# ctest COST of the suite's slowest tests (issue 31), included by ctest after the test executables'
# discovered tests (TEST_INCLUDE_FILES, see tests/CMakeLists.txt).
#
# Why: ctest -j N starts tests in descending COST, and without a CTestCostData.txt (every clean clone,
# every CI machine) all costs are equal, so tests start in registration order: in the quiet cold
# `make test` of main 639eb7b the 394 s `reproduce gomez2024 --quick` started as test 350 of 519 and
# finished last, 642 s of ctest for 1213 s of tests on 2 cores. Started first, it runs beside the rest.
# Once a build folder has its own CTestCostData.txt, ctest uses those measured costs instead.
#
# The costs are the seconds of every test that took 5 s or more in the quiet cold `make test` of main
# 73bce7f (2-core machine, load 0 before, 27 Nov 2026 10:27-10:40 UTC, Release, ctest -j2; the lead's
# /work/notes/s14/cold.log, its build/Testing/Temporary/CTestCostData.txt), rounded. A name that no
# longer matches a test is ignored by ctest, so tests/docs checks that every name here is a registered test.
set_tests_properties([=[reproduce:reproduce gomez2024 --quick: Fig. 3, Fig. 4, timing and study within tolerance]=] PROPERTIES COST 331)
set_tests_properties([=[stimuli:demo stimuli at 640x360: not blank, characters where predicted, less red once corrected]=] PROPERTIES COST 147)
set_tests_properties([=[correction:correction: the foot motion budget stops feet jumping in the densest corridor]=] PROPERTIES COST 109)
set_tests_properties([=[study:browser: lab and online show the same screens, headers and texts (demo, 2AFC pairs, consent + breaks + two blocks)]=] PROPERTIES COST 67)
set_tests_properties([=[fuzz:mutated crowd GLBs through correct, metrics, export-csv and the motion importer]=] PROPERTIES COST 64)
set_tests_properties([=[pipeline:plan --emit slurm: the script runs on a real single-node Slurm cluster]=] PROPERTIES COST 44)
set_tests_properties([=[study:browser: a scripted participant completes the demo study in headless Chromium, resumes after a reload]=] PROPERTIES COST 43)
set_tests_properties([=[analysis:analyze report: every simulated study gets a report with finite or 'Not fitted' cells]=] PROPERTIES COST 42)
set_tests_properties([=[fuzz:mutated specs through validate end in exit 0 or 2 with a message]=] PROPERTIES COST 41)
set_tests_properties([=[fuzz:mutated analysis CSVs through analyze anova end in exit 0 or 2 with a message]=] PROPERTIES COST 36)
set_tests_properties([=[study:browser: under JATOS the id comes from JATOS, every record and the consent are appended in order, the study ends after the last append, and the appended lines import as the download does]=] PROPERTIES COST 34)
set_tests_properties([=[reproduce:reproduce hoyet2016 --quick: Fig. 3, Table 1 and Table 2 within tolerance]=] PROPERTIES COST 28)
set_tests_properties([=[study:participant test: the real window under Xvfb, driven by xdotool, killed and resumed]=] PROPERTIES COST 28)
set_tests_properties([=[pipeline:stage redo: the stimuli's look redoes the clips and the contact sheets, the encoding the clips]=] PROPERTIES COST 17)
set_tests_properties([=[fuzz:mutated BVH clips through the importer and retargeting end in success or InputError]=] PROPERTIES COST 17)
set_tests_properties([=[fuzz:hostile families of issue 33 are refused with exit 2, naming the file or option]=] PROPERTIES COST 16)
set_tests_properties([=[pipeline:run: killed at several stages and resumed, the outputs equal an uninterrupted run's]=] PROPERTIES COST 13)
set_tests_properties([=[fuzz:hostile families of issue 32 are refused with exit 2, within the caps]=] PROPERTIES COST 13)
set_tests_properties([=[pipeline:stage redo: a crowd, animation or correction change redoes its stage and exactly its dependants]=] PROPERTIES COST 12)
set_tests_properties([=[pipeline:shards are disjoint, collect merges them, and the result equals an unsharded run]=] PROPERTIES COST 11)
set_tests_properties([=[correction:correction: joints that touch nobody keep their input, and no joint flips]=] PROPERTIES COST 11)
set_tests_properties([=[pipeline:run on a full disk: exit 1, the file and the OS's reason named, no temporary left]=] PROPERTIES COST 11)
set_tests_properties([=[pipeline:plan writes Slurm, GNU parallel and make job files]=] PROPERTIES COST 10)
set_tests_properties([=[study:browser: a declined consent is recorded online and imported as natively]=] PROPERTIES COST 10)
set_tests_properties([=[io:hand-mutated GLBs exit 2 from correct, metrics and export-csv, saying what is wrong and where]=] PROPERTIES COST 9)
set_tests_properties([=[determinism:pinned output hash: every stage's outputs are unchanged with 1 and 2 threads]=] PROPERTIES COST 9)
set_tests_properties([=[correction:correction: planted feet stay at the input's height, so bodies do not float]=] PROPERTIES COST 9)
set_tests_properties([=[correction:correction cli: running out of memory is named by the command, not by std::bad_alloc]=] PROPERTIES COST 9)
set_tests_properties([=[pipeline:run: a deleted crowd file is recomputed and everything downstream equals an uninterrupted run]=] PROPERTIES COST 8)
set_tests_properties([=[study:full screen on an X server without a window manager covers the real screen]=] PROPERTIES COST 8)
set_tests_properties([=[pipeline:every other command that writes an output folder is refused while another holds it]=] PROPERTIES COST 7)
set_tests_properties([=[pipeline:stage redo: a text-only protocol edit redoes no stage, and the contact sheets are made]=] PROPERTIES COST 7)
set_tests_properties([=[pipeline:simulated observers analysed by the report: paired items agree and the method effect shows]=] PROPERTIES COST 6)
set_tests_properties([=[study:crowdlab study --responses: a scripted session, used ids refused, corrupted stimuli caught]=] PROPERTIES COST 6)
set_tests_properties([=[stimuli:crowdlab render: glb -> mp4 with the overlap CSV, and exit 2 for odd sizes, unknown viewpoints, missing files]=] PROPERTIES COST 5)
set_tests_properties([=[fuzz:the fuzz harness reports a signal, a hang, memory over the cap and a silent exit 2]=] PROPERTIES COST 5)
set_tests_properties([=[pipeline:run makes every condition's crowd, metrics and clip, then reuses them]=] PROPERTIES COST 5)
set_tests_properties([=[pipeline:run: a truncated clip beside its old sidecar is re-rendered, and no temporary is left]=] PROPERTIES COST 5)
set_tests_properties([=[correction:follow root offsets: the dense corridor corrected twice follows its pushed roots with fewer flips and less float, in twice the steps]=] PROPERTIES COST 6)
