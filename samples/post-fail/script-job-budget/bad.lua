-- Each on_block just under its budget: the job's budget (script_instructions) stops it.
function on_block(text)
  for i = 1, 100000 do end
  return text
end
