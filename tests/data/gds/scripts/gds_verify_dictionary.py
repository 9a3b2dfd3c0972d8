# Reference only: run with the fprime-gds 4.4.1 venv python; NOT collected by the project test-suite.
from fprime_gds.common.models.dictionaries import Dictionaries
from fprime_gds.common.loaders.prm_json_loader import PrmJsonLoader
from fprime_gds.common.utils.config_manager import ConfigManager
D = str(__import__("pathlib").Path(__file__).resolve().parent.parent / "minimal_dictionary.json")
d = Dictionaries.load_dictionaries_into_config(D)
print("commands:", {k: v.get_id() for k, v in d.command_name.items()})
print("events:", {k: v.get_id() for k, v in d.event_name.items()})
print("channels:", {k: v.get_id() for k, v in d.channel_name.items()})
print("typedefs:", {k: v.__name__ for k, v in d.typedefs_name.items()})
print("constants:", d.constant_name, "metadata:", d.metadata, "packets:", d.packet)
prm = PrmJsonLoader(D)
print("params:", {k: (v.prm_id, v.prm_type_obj.__name__) for k, v in prm.get_name_dict(None).items()})
cmd = d.command_name["MiniDep.demo.CONFIGURE"]
print("CONFIGURE comp/mnemonic/args:", cmd.get_comp_name(), cmd.get_name(), [(a[0], a[2].__name__) for a in cmd.get_args()])
ev = d.event_name["MiniDep.demo.Configured"]
print("event fmt:", repr(ev.get_format_str()), ev.get_severity())
cm = ConfigManager()
for t in ["FwOpcodeType","FwSizeStoreType","FwPacketDescriptorType","TimeBase","ComCfg.Apid","FwTimeContextStoreType"]:
    print(t, "->", cm.get_type(t).__name__)
G = cm.get_type("Demo.Gains"); print("Gains members:", [(m[0], m[1].__name__, m[2]) for m in G.MEMBER_LIST])
