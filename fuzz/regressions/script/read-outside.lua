function on_record(rec)
  post.emit("(" .. post.read_file("passwd") .. ")")
end
function on_block(text)
  local f = post.read_file("fifo")
  return text
end
function on_program_end() while true do post.read_file("tools.csv") end end
