# cmake -DIN=<bundle.js> -DTEMPLATE=<viewer_asset.cpp.in> -DOUT=<viewer_asset.cpp> -P embed_viewer.cmake
# Puts the bundled viewer into a C++ raw string literal; refuses a bundle that could not sit inside an HTML
# <script> element or the literal.
if(NOT EXISTS "${IN}")
  message(FATAL_ERROR "${IN}: the bundled report viewer is missing (target centaur_viewer_bundle: npm ci and esbuild "
                      "in <build>/web; see docs/report.md)")
endif()
file(READ "${IN}" CENTAUR_VIEWER_JS)
string(LENGTH "${CENTAUR_VIEWER_JS}" length)
if(length LESS 1000)
  message(FATAL_ERROR "${IN}: the bundled report viewer is missing or empty")
endif()
string(TOLOWER "${CENTAUR_VIEWER_JS}" lower)
foreach(bad "</script" "<!--" ")centaur_viewer\"")
  string(FIND "${lower}" "${bad}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "${IN}: the bundled viewer contains '${bad}' (at ${at}); it cannot be embedded in the page")
  endif()
endforeach()
file(SHA256 "${IN}" CENTAUR_VIEWER_SHA256)
configure_file("${TEMPLATE}" "${OUT}.tmp" @ONLY)
file(RENAME "${OUT}.tmp" "${OUT}")
