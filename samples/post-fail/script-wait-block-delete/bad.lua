-- A wait under block delete, paired in both channels: the block delete switch skips it.
function on_program_start(ctx)
  post.emit("/M101")
end
