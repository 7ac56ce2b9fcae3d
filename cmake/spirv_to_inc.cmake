# cmake -DINPUT=x.spv -DOUTPUT=x.spv.inc -P spirv_to_inc.cmake: a SPIR-V binary as comma-separated
# 32-bit words (little-endian), the format glslc -mfmt=num writes, for #include into a C++ array.
file(READ ${INPUT} hex HEX)
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1," words "${hex}")
file(WRITE ${OUTPUT} "${words}\n")
