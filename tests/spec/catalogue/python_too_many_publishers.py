# error: python_too_many_publishers.py:10:8: the scheduler of the publishers needs between 1 and 1024 inputs, not 1025
# hint: the paper evaluates N = 2 … 256
import rfc

project = rfc.Project("Catalogue")
sub = project.subscriber("Byte_sub", "std_msgs/UInt8")
publishers = [project.publisher(f"Byte_pub{i}", "std_msgs/UInt8") for i in range(1024)]
for publisher in publishers:
    sub >> publisher
sub >> project.publisher("Byte_pub1024", "std_msgs/UInt8")
