function on_block(text)
  for i = 1, 24990 do end
  return text
end
