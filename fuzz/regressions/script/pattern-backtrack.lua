function on_block(text)
  return (string.find(string.rep("a", 1e5), ".-.-.-.-b")) and text or text
end
