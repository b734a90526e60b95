-- bench/bench-lathe-script.toml: every block passes on_block, kept as it is.
function on_block(text, ctx)
  return text
end
