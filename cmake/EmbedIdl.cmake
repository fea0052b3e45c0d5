# Writes OUT: a C++ source holding the text of every IDL file (for MCAP schemas).
# Inputs: -DIDL_DIR=... -DOUT=...
file(GLOB_RECURSE files RELATIVE ${IDL_DIR} ${IDL_DIR}/*.idl)
list(SORT files)
set(body "// Generated from idl/ by cmake/EmbedIdl.cmake: do not edit.\n#include <map>\n#include <string>\n\nnamespace ltm::runtime {\n\nconst std::map<std::string, std::string>& idl_sources() {\n    static const std::map<std::string, std::string> sources = {\n")
foreach(f ${files})
  file(READ ${IDL_DIR}/${f} text)
  string(APPEND body "        {\"${f}\", R\"ltmidl(${text})ltmidl\"},\n")
endforeach()
string(APPEND body "    };\n    return sources;\n}\n\n}  // namespace ltm::runtime\n")
file(WRITE ${OUT}.tmp "${body}")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different ${OUT}.tmp ${OUT})
