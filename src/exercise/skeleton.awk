# skeleton.awk - lessons/NN-name/exercise.c from the worked answer beside it,
# answer.c (and a graded variant's exercise-V.c from answer-V.c)
# (`make skeletons`; tests/test_exercise.c holds the committed skeleton to it).
#
# The answer is the one source. It opens with its own comment, "Answer to
# exercise NN: ...", then the skeleton's, whose first line " * Exercise NN:"
# (or " * Exercise NN, variant V:") becomes the skeleton's "/* Exercise NN:". The student's parts are marked:
#
#     #if SKELETON        what the skeleton has (the TODO's stand-in)
#     #else               what the answer writes
#     #endif
#
# or "#if !SKELETON ... #endif" for lines of the answer alone. SKELETON is
# never defined, so the answer compiles as it reads.
NR == 1 && /^\/\* Answer to exercise/ { intro = 1 }
intro {
    if ($0 ~ /^ \* Exercise [0-9][0-9][,:]/) {
        sub(/^ \*/, "/*")
        intro = 0
        print
    }
    next
}
/^#if SKELETON$/ { mode = "skeleton"; next }
/^#if !SKELETON$/ { mode = "answer"; next }
/^#else$/ && mode == "skeleton" { mode = "answer"; next }
/^#endif$/ && mode != "" { mode = ""; next }
mode == "answer" { next }
{ print }
