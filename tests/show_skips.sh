#!/usr/bin/env bash
# Run by ctest after the tests (CTEST_CUSTOM_POST_TEST, tests/CMakeLists.txt): one line per skip
# in the run's log, with its reason: the line after GoogleTest's "FILE:LINE: Skipped", or a
# script's "SKIP: ..." line (a whole script skipped, exit 77, or a part of one). Never fails.
# The log is LastTest.log.tmp until ctest ends (renamed after this script has run).
log=${1:-Testing/Temporary/LastTest.log.tmp}
[ -f "$log" ] || exit 0
awk '
  /^[0-9]+\/[0-9]+ Test: / { sub(/^[0-9]+\/[0-9]+ Test: /, ""); name = $0; next }
  reason { reason = 0; if ($0 !~ /^\[/) { lines[++n] = name ": " $0 }; next }
  /: Skipped$/ { reason = 1; next }
  /^SKIP: / { sub(/^SKIP: /, ""); lines[++n] = name ": " $0 }
  END {
    if (n) print "Skip reasons:"
    for (i = 1; i <= n; i++) print "\t" lines[i]
  }
' "$log"
exit 0
