function on_program_start() post.emit(string.rep("X1.", 1e6)) end
function on_tool_change() while true do post.emit("G4 X1.") end end
function on_record() post.emit("%") end
function on_block(text) return "M30\0" end
function on_program_end() while true do post.warning("\27[2J\27]0;pwned\7") end end
