# Reference only: run with the fprime-gds 4.4.1 venv python; NOT collected by the project test-suite.
def test_configure(fprime_test_api):
    res = fprime_test_api.send_and_assert_command("MiniDep.demo.CONFIGURE", ["7", "2.5", "hello", "NOMINAL"], timeout=5)
    assert len(res) == 2
    fprime_test_api.assert_event("MiniDep.demo.Configured", args=[7, 2.5, "hello", "NOMINAL"], timeout=3)
    ch = fprime_test_api.await_telemetry("MiniDep.demo.Voltage", timeout=3)
    assert ch is not None and abs(ch.get_val() - 3.3) < 1e-5
    fprime_test_api.send_and_assert_command("CdhCore.cmdDisp.CMD_NO_OP", max_delay=1.0)
