# Included by tests/CMakeLists.txt (so that the Wine block there covers these tests too).
# The programs are built always (clang-tidy reads every source); the tests need the course
# scenes and keys, as the golden tests do, and are left out where those are absent.
set(fake_modes black pixel64 one_level hang segfault exit1 wrong_size wrong_name p3 shifted huge_header escapes lax_header
               straggler trailing dozen_steps ambiguous_sides sparse_tail endless_comment waits_for_enter endless_stderr fifo_output
               readonly_folder link_to_key stdout_null)
foreach(mode ${fake_modes})
  add_executable(fake_${mode} grade/fake_renderer.cpp)
  target_compile_definitions(fake_${mode} PRIVATE FAKE_MODE="${mode}")
  if(NOT MSVC)
    # The warnings of raytracer_warnings, not its sanitizers (fake_renderer.cpp says why).
    target_compile_options(fake_${mode} PRIVATE -Wall -Wextra -Wpedantic
                           $<$<BOOL:${RAYTRACER_WARNINGS_AS_ERRORS}>:-Werror>)
  endif()
endforeach()
if(NOT WIN32)
  add_executable(grade_interrupt grade/interrupt.cpp check_main.cpp)
  target_link_libraries(grade_interrupt PRIVATE raytracer_warnings)
  target_compile_definitions(grade_interrupt PRIVATE RAYTRACER_GRADE="$<TARGET_FILE:raytracer-grade>"
                             FAKE_HANG="$<TARGET_FILE:fake_hang>" FAKE_ONE_LEVEL="$<TARGET_FILE:fake_one_level>"
                             FAKE_STRAGGLER="$<TARGET_FILE:fake_straggler>"
                             FAKE_WAITS_FOR_ENTER="$<TARGET_FILE:fake_waits_for_enter>"
                             FAKE_READONLY_FOLDER="$<TARGET_FILE:fake_readonly_folder>" COURSE_SCENES="${course_scene_dir}")
endif()
# The ambiguous pixels' other outcomes (ambiguous_pixels.cpp), derived from the course scenes.
add_executable(ambiguous_outcomes grade/ambiguous_outcomes.cpp check_main.cpp)
target_link_libraries(ambiguous_outcomes PRIVATE raytracer_grade_parts raytracer_warnings)
target_compile_definitions(ambiguous_outcomes PRIVATE RAYTRACER_COURSE_TESTS="${RAYTRACER_COURSE_TESTS}")
if(NOT EXISTS "${course_scene_dir}/testShadow.txt")
  return()
endif()
add_test(NAME grade.ambiguous-outcomes COMMAND ambiguous_outcomes)

set(grade_out "${CMAKE_CURRENT_BINARY_DIR}/grade-out")
set(GRADE_SCENES "${course_scene_dir}")  # the scene folder each grade_test() passes last
# grade_test(NAME MODE STATUS EXPECT [ARGS ...]): EXPECT is a '|'-separated list of texts.
function(grade_test name mode status expect)
  list(JOIN ARGN "|" args)
  add_test(NAME grade.${name}
           COMMAND ${CMAKE_COMMAND} -DGRADER=$<TARGET_FILE:raytracer-grade> "-DEMULATOR=${CMAKE_CROSSCOMPILING_EMULATOR}"
                   "-DARGS=--raytracer|$<TARGET_FILE:fake_${mode}>|${args}|${GRADE_SCENES}" -DSTATUS=${status}
                   "-DEXPECT=${expect}" "-DREJECT=total: 0 differing|${GRADE_REJECT}" ${GRADE_EXTRA}
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/grade/expect.cmake)
  set_tests_properties(grade.${name} PROPERTIES TIMEOUT 120)
endfunction()

if(WIN32)
  set(segfault_message "crashed with an access violation (0xC0000005, like SIGSEGV)")
else()
  set(segfault_message "killed by SIGSEGV")
endif()
grade_test(black black 1 "testShadow|FAIL   0/2|359998 pixels differ from the key; 8 by one level (allowed); 359990 unexplained, largest 255 levels|the unexplained pixels lie in x 0..599, y 0..599|(0, 0): key 255 255 255, got 0 0 0|(4, 0): key 255 255 255, got 0 0 0|... and 359985 more|marks 0/2: 0 of 1 scene passes; 1 differs beyond the rule: FAIL" --only testShadow)
grade_test(pixel64 pixel64 1 "1 pixel differs from the key; 1 unexplained, largest 64 levels|the unexplained pixels lie in x 300..300, y 200..200|(300, 200): key 44 0 0, got 108 0 0|marks 0/2" --only testIllum)
# A dozen pixels one level off pass; every pixel one level off (rounding, not truncating)
# does not.
grade_test(dozen-steps dozen_steps 0 "testShadow                  12           0|marks 24/24: all 12 scenes pass: PASS")
# A known ambiguous pixel may show its other outcome, not a third colour.
grade_test(ambiguous-sides ambiguous_sides 1 "testShadow                   2           1|2 pixels differ from the key; 1 known ambiguous showing the other outcome (allowed); 1 unexplained, largest 255 levels|(375, 200): key 0 0 0, got 0 0 255 (a known ambiguous pixel: its other outcome is 255 255 255)" --only testShadow)
grade_test(one-level one_level 1 "testShadow              360000           0|360000 pixels differ from the key; 360000 by one level, more than the 12 truncation steps allowed|marks 0/24: 0 of 12 scenes pass; 12 differ beyond the rule: FAIL")
grade_test(hang hang 1 "still running after 1 s (--timeout): killed|marks 0/2" --timeout 1 --only testAmbient)
grade_test(segfault segfault 1 "testSample|${segfault_message}|marks 0/24: 0 of 12 scenes pass; 12 gave no image to compare: FAIL")
grade_test(exit1 exit1 1 "exited with status 1: fake: error: cannot open the scene file|marks 0/2" --only testParsing)
grade_test(wrong-size wrong_size 1 "wrote 300x300, the key is 600x600|marks 0/2" --only testDiffuse)
grade_test(wrong-name wrong_name 1 "wrote nothing named testSample.ppm (OUTPUT of the scene); it wrote: a.ppm|marks 0/2" --only testSample)
grade_test(shifted shifted 1 "19950 pixels differ from the key; 8620 by one level, more than the 12 truncation steps allowed (a systematic difference: rounding, not truncating?); 3 known ambiguous showing the other outcome (allowed); 11327 unexplained|the unexplained pixels lie in x 149..455, y 146..451|(412, 146): key 64 0 0, got 255 255 255" --only testShadow)
grade_test(p3 p3 1 "P3 written; the course requires P6|marks 0/2" --only testBehind)

# The pictures: --diff-dir writes one PNG per failing scene, --html one page showing them.
set(GRADE_EXTRA -DCLEAN=${grade_out}/html "-DFILES=${grade_out}/html/diffs/testIllum.png"
                -DPAGE=${grade_out}/html/grade.html
                "-DPAGE_EXPECT=<img src=\"diffs/testIllum.png\"|(300, 200): key 44 0 0, got 108 0 0|<td>FAIL</td>")
grade_test(html pixel64 1 "picture (key | yours | difference): ${grade_out}/html/diffs/testIllum.png|page: ${grade_out}/html/grade.html"
           --only testIllum --diff-dir ${grade_out}/html/diffs --html ${grade_out}/html/grade.html)
set(GRADE_EXTRA -DCLEAN=${grade_out}/html-alone "-DFILES=${grade_out}/html-alone/marks-pictures/testShadow.png"
                -DPAGE=${grade_out}/html-alone/marks.html "-DPAGE_EXPECT=<img src=\"marks-pictures/testShadow.png\"")
grade_test(html-alone black 1 "marks 0/2" --only testShadow --html ${grade_out}/html-alone/marks.html)
if(NOT WIN32)
  # A page in a folder reached through a symbolic link: its links are lexical, as the
  # browser resolves them from the page's own address, not from the link's target.
  set(GRADE_EXTRA -DCLEAN=${grade_out}/html-link "-DLINK=${grade_out}/html-link/real/deep|${grade_out}/html-link/via"
                  -DPAGE=${grade_out}/html-link/via/page.html "-DPAGE_EXPECT=<img src=\"../pictures/testShadow.png\"")
  grade_test(html-link black 1 "marks 0/2" --only testShadow --diff-dir ${grade_out}/html-link/pictures
             --html ${grade_out}/html-link/via/page.html)
endif()
unset(GRADE_EXTRA)

# Ways a renderer can go wrong that the grader must neither trust nor pass to the terminal.
grade_test(trailing-bytes trailing 0 "note: 5 bytes after the pixels, where a P6 file ends|marks 2/2" --only testShadow)
grade_test(huge-header huge_header 1 "wrote 30000x30000, the key is 600x600|marks 0/2" --only testShadow)
if(NOT WIN32)
  # 64 GiB after the pixels or in a header comment (sparse files; Wine's resize_file()
  # refuses the size): counted from the file's size, and refused past 64 KiB, not read
  # (about 2.5 s a GB: far past the test's 120 s).
  grade_test(sparse-tail sparse_tail 0 "note: 68719476736 bytes after the pixels, where a P6 file ends|marks 2/2" --only testShadow)
  grade_test(endless-comment endless_comment 1 "'testShadow.ppm' has a header of over 64 KiB, expected a binary PPM (P6)|marks 0/2" --only testShadow)
  # 64 GiB of stderr without a newline: its first 64 KiB read (escaped NUL bytes, cut).
  grade_test(endless-stderr endless_stderr 1 "exited with status 1: \\x00\\x00|marks 0/2" --only testShadow)
  grade_test(fifo-output fifo_output 1 "wrote a FIFO named testShadow.ppm (OUTPUT of the scene), not a file|marks 0/2" --only testShadow)
  # A link to the key is no image written: the file itself is judged, not the link's target.
  # Nothing of the program's standard output is read: it goes to the null device, not to
  # a file that a chatty program would fill.
  grade_test(stdout-null stdout_null 0 "marks 2/2" --only testShadow)
  grade_test(link-to-key link_to_key 1 "wrote a symbolic link named testShadow.ppm (OUTPUT of the scene), not a file|marks 0/2" --only testShadow)
endif()
# (no brackets in the expected texts: CMake's lists do not split inside them)
grade_test(escapes escapes 1 "exited with status 3: \\x1b|mred\\x1b|m \\x07|marks 0/2" --only testShadow)

# The command line: a scene folder with a trailing separator, options as --name=value and
# --only with the file's name, each option at most once, one scene folder.
set(GRADE_SCENES "${course_scene_dir}/")
grade_test(trailing-separator dozen_steps 0 "marks 2/2: the scene passes: PASS" --only=testShadow.txt --timeout=60)
set(GRADE_SCENES "${course_scene_dir}")
grade_test(option-twice one_level 2 "--only given twice" --only testShadow --only testAmbient)
grade_test(two-folders one_level 2 "two scene folders" ${course_scene_dir})
grade_test(only-naming-no-scene one_level 2 "no scene testNothing.txt in" --only testNothing)
grade_test(html-onto-a-folder one_level 2 "is not a file, expected a new or replaceable page"
           --only testShadow --html ${CMAKE_CURRENT_BINARY_DIR})
# --html naming a scene being graded: refused before anything is written, on a copy.
set(GRADE_EXTRA -DCLEAN=${grade_out}/refuse "-DCOPY=${course_scene_dir}/testShadow.txt|${grade_out}/refuse/scenes|${course_scene_dir}/../keys/keyShadow.ppm|${grade_out}/refuse/keys"
                -DPAGE=${grade_out}/refuse/scenes/testShadow.txt "-DPAGE_EXPECT=OUTPUT")
set(GRADE_SCENES "${grade_out}/refuse/scenes")
grade_test(html-onto-a-scene one_level 2 "is a scene being graded, expected a new or replaceable page"
           --html ${grade_out}/refuse/scenes/testShadow.txt)
# ... or any other file of the scene or key folder, which --only leaves out.
set(GRADE_EXTRA -DCLEAN=${grade_out}/refuse-other "-DCOPY=${course_scene_dir}/testShadow.txt|${grade_out}/refuse-other/scenes|${course_scene_dir}/testAmbient.txt|${grade_out}/refuse-other/scenes|${course_scene_dir}/../keys/keyShadow.ppm|${grade_out}/refuse-other/keys"
                -DPAGE=${grade_out}/refuse-other/scenes/testAmbient.txt "-DPAGE_EXPECT=OUTPUT")
set(GRADE_SCENES "${grade_out}/refuse-other/scenes")
grade_test(html-onto-another-scene one_level 2 "is a scene of the scene folder, expected a new or replaceable page"
           --only testShadow --html ${grade_out}/refuse-other/scenes/testAmbient.txt)
# Another file there (a page of an earlier run, here a copy of a script) is replaced.
set(GRADE_EXTRA -DCLEAN=${grade_out}/page-beside "-DCOPY=${course_scene_dir}/testShadow.txt|${grade_out}/page-beside/scenes|${CMAKE_CURRENT_SOURCE_DIR}/grade/check_screenshot.py|${grade_out}/page-beside/scenes|${course_scene_dir}/../keys/keyShadow.ppm|${grade_out}/page-beside/keys"
                -DPAGE=${grade_out}/page-beside/scenes/check_screenshot.py "-DPAGE_EXPECT=marks 2/2")
set(GRADE_SCENES "${grade_out}/page-beside/scenes")
grade_test(html-beside-the-scenes dozen_steps 0 "marks 2/2: the scene passes: PASS"
           --html ${grade_out}/page-beside/scenes/check_screenshot.py)
set(GRADE_SCENES "${course_scene_dir}")
unset(GRADE_EXTRA)

# Keys whose headers claim what the file does not hold: each scene says so, the others are
# graded (a 6.3 GB claim costs no 6.3 GB; 2^31 x 1 pixels is refused from the header).
set(GRADE_EXTRA -DCLEAN=${grade_out}/bad-keys "-DCOPY=${course_scene_dir}/testShadow.txt|${grade_out}/bad-keys/scenes|${course_scene_dir}/testSample.txt|${grade_out}/bad-keys/scenes|${course_scene_dir}/testAmbient.txt|${grade_out}/bad-keys/scenes|${course_scene_dir}/../keys/keyShadow.ppm|${grade_out}/bad-keys/keys|${CMAKE_CURRENT_SOURCE_DIR}/grade/bad_keys/keySample.ppm|${grade_out}/bad-keys/keys|${CMAKE_CURRENT_SOURCE_DIR}/grade/bad_keys/keyAmbient.ppm|${grade_out}/bad-keys/keys")
set(GRADE_SCENES "${grade_out}/bad-keys/scenes")
grade_test(bad-keys dozen_steps 1 "testSample                   -           -    0.000  FAIL   0/2  no usable key: '|keySample.ppm' is a P6 of 2147483648x1 pixels, more than the 2^31 - 1 read|keyAmbient.ppm' is shorter than its header says|testShadow                  12           0|marks 2/6: 1 of 3 scenes pass; 2 without a readable scene or key to grade by: FAIL")
# A renderer's header that a PPM reader refuses is not read for its numbers.
set(GRADE_SCENES "${course_scene_dir}")
unset(GRADE_EXTRA)
grade_test(lax-header lax_header 1 "'testShadow.ppm' is not a binary PPM (P6) with maxval 255|marks 0/2" --only testShadow)
# An OUTPUT outside the run's folder would grade a file that was there before the run.
set(GRADE_SCENES "${CMAKE_CURRENT_SOURCE_DIR}/grade/outside/scenes")
grade_test(output-outside one_level 1 "OUTPUT '../testOutside.ppm' is outside the run's folder, expected a file name in it|marks 0/2")
set(GRADE_SCENES "${course_scene_dir}")

grade_test(help one_level 0 "usage: raytracer-grade [--raytracer EXE]|every channel is off by at most one level|ambiguous pixels" --help)
grade_test(bad-timeout one_level 2 "--timeout 'soon' is not a number of seconds" --timeout soon)
grade_test(hex-timeout one_level 2 "--timeout '0x10' is not a number of seconds" --timeout 0x10)

# Interrupting the grader while a render hangs (POSIX signals; on Windows, Ctrl-C is not
# sent to a program under Wine by CTest).
if(NOT WIN32)
  add_test(NAME grade.interrupt COMMAND grade_interrupt)
endif()
