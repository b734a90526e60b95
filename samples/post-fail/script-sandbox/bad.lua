-- A script that reaches outside the sandbox: os is not there.
function on_program_start(ctx)
  os.execute("rm -rf /tmp/x")
end
