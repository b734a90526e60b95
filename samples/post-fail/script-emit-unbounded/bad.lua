-- Blocks without end: the job's limit on what a script writes.
function on_program_start(ctx)
  local b = "(" .. string.rep("X", 4000) .. ")"
  while true do post.emit(b) end
end
