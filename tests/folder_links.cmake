# Makes the folder links of cli.faults's Windows test under Wine, where a Windows program
# can make none that Wine follows: FOLDER/work/escape links out to FOLDER/elsewhere,
# FOLDER/work/alias to FOLDER/work/inside. Run on the host: cmake -DFOLDER=... -P this.
file(REMOVE_RECURSE "${FOLDER}")
file(MAKE_DIRECTORY "${FOLDER}/elsewhere" "${FOLDER}/work/inside")
file(CREATE_LINK "${FOLDER}/elsewhere" "${FOLDER}/work/escape" SYMBOLIC)
file(CREATE_LINK "inside" "${FOLDER}/work/alias" SYMBOLIC)
